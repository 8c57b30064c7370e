//! The run-time side of every `--max-time`: a point in time after which running work gives
//! up. Long loops (texels, albedos, fits) check it between items; the work is then an error
//! and nothing is written.

/// A point in time after which a running bake gives up (the run-time side of `--max-time`,
/// for inputs the estimate underrates: it is checked before every texel).
#[derive(Clone, Copy, Debug)]
pub struct Deadline {
    pub at: std::time::Instant,
    /// The limit it was made from, for messages.
    pub seconds: f64,
}

impl Deadline {
    /// `seconds` from now (far in the future if that overflows `Instant`).
    pub fn after(seconds: f64) -> Deadline {
        let now = std::time::Instant::now();
        let d = std::time::Duration::try_from_secs_f64(seconds)
            .unwrap_or(std::time::Duration::from_secs(u32::MAX as u64));
        Deadline {
            at: now
                .checked_add(d)
                .unwrap_or(now + std::time::Duration::from_secs(1 << 30)),
            seconds,
        }
    }

    pub fn passed(&self) -> bool {
        std::time::Instant::now() >= self.at
    }
}

thread_local! {
    /// The deadline of the work this thread runs for ([`scoped`]), for rules deep in a
    /// computation (a 2D quadrature) that take no deadline argument.
    static CURRENT: std::cell::Cell<Option<Deadline>> = const { std::cell::Cell::new(None) };
}

/// Runs `f` with `d` as this thread's current deadline ([`current_passed`]).
pub fn scoped<T>(d: Deadline, f: impl FnOnce() -> T) -> T {
    let before = CURRENT.with(|c| c.replace(Some(d)));
    let out = f();
    CURRENT.with(|c| c.set(before));
    out
}

/// Whether this thread's current deadline ([`scoped`]) has passed (`false` without one).
pub fn current_passed() -> bool {
    CURRENT.with(|c| c.get()).is_some_and(|d| d.passed())
}
