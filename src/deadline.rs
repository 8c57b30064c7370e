//! The run-time side of every `--max-time`: a point in time after which running work gives
//! up. Long loops (texels, albedos, fits) check it between items; the work is then an error
//! and nothing is written.
//!
//! The same check stops work cancelled from outside: an embedder that cannot send a signal
//! into the loops (the Python module, whose Ctrl-C is a flag the interpreter raises later)
//! runs a command inside [`cancellable`], and every deadline made there passes once the flag
//! is set.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A point in time after which a running bake gives up (the run-time side of `--max-time`,
/// for inputs the estimate underrates: it is checked before every texel), or earlier when
/// its cancel flag is set ([`cancellable`]).
#[derive(Clone, Debug)]
pub struct Deadline {
    pub at: std::time::Instant,
    /// The limit it was made from, for messages.
    pub seconds: f64,
    /// The flag of the [`cancellable`] scope the deadline was made in.
    cancel: Option<Arc<AtomicBool>>,
}

thread_local! {
    /// The cancel flag of the [`cancellable`] scope running on this thread.
    static CANCEL: RefCell<Option<Arc<AtomicBool>>> = const { RefCell::new(None) };
}

impl Deadline {
    /// `seconds` from now (far in the future if that overflows `Instant`), cancelled with the
    /// flag of the [`cancellable`] scope this thread runs in, if any.
    pub fn after(seconds: f64) -> Deadline {
        let now = std::time::Instant::now();
        let d = std::time::Duration::try_from_secs_f64(seconds)
            .unwrap_or(std::time::Duration::from_secs(u32::MAX as u64));
        Deadline {
            at: now
                .checked_add(d)
                .unwrap_or(now + std::time::Duration::from_secs(1 << 30)),
            seconds,
            cancel: CANCEL.with_borrow(Clone::clone),
        }
    }

    /// Whether the work must stop: the time is up, or it was cancelled.
    pub fn passed(&self) -> bool {
        self.cancelled() || std::time::Instant::now() >= self.at
    }

    /// Whether the deadline's cancel flag is set (the work stops as at its time limit).
    pub fn cancelled(&self) -> bool {
        self.cancel
            .as_ref()
            .is_some_and(|c| c.load(Ordering::Relaxed))
    }
}

/// Runs `f` with `flag` as the cancel flag of every [`Deadline`] made on this thread while
/// it runs: once the flag is set (from any thread), those deadlines have passed and the work
/// they guard stops as at its time limit — an error, nothing written — within one item of
/// its loop (a texel, an albedo, a fit). Scopes nest; the previous flag is restored after.
pub fn cancellable<R>(flag: Arc<AtomicBool>, f: impl FnOnce() -> R) -> R {
    /// Restores the enclosing scope's flag, also when `f` unwinds.
    struct Restore(Option<Arc<AtomicBool>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            CANCEL.set(self.0.take());
        }
    }
    let _restore = Restore(CANCEL.replace(Some(flag)));
    f()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cancelled_deadline_has_passed_and_only_inside_its_scope() {
        let flag = Arc::new(AtomicBool::new(false));
        let outside = Deadline::after(600.0);
        let inside = cancellable(flag.clone(), || Deadline::after(600.0));
        let after = Deadline::after(600.0);
        assert!(!inside.passed() && !outside.passed());
        flag.store(true, Ordering::Relaxed);
        assert!(inside.passed() && inside.cancelled());
        assert!(
            !outside.passed() && !after.passed(),
            "made outside the scope"
        );
        assert!(Deadline::after(0.0).passed());
    }
}

thread_local! {
    /// The deadline of the work this thread runs for ([`scoped`]), for rules deep in a
    /// computation (a 2D quadrature) that take no deadline argument.
    static CURRENT: RefCell<Option<Deadline>> = const { RefCell::new(None) };
}

/// Runs `f` with `d` as this thread's current deadline ([`current_passed`]); the enclosing
/// one is restored after, also when `f` unwinds.
pub fn scoped<T>(d: &Deadline, f: impl FnOnce() -> T) -> T {
    struct Restore(Option<Deadline>);
    impl Drop for Restore {
        fn drop(&mut self) {
            CURRENT.set(self.0.take());
        }
    }
    let _restore = Restore(CURRENT.replace(Some(d.clone())));
    f()
}

/// Whether this thread's current deadline ([`scoped`]) has passed (`false` without one).
pub fn current_passed() -> bool {
    CURRENT.with_borrow(|c| c.as_ref().is_some_and(Deadline::passed))
}
