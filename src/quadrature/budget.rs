//! A per-integral evaluation budget shared by nested adaptive integrations.
//!
//! Each adaptive rule has its own `max_evals`, but a nested integral (an average albedo
//! over μ of hemisphere integrals, the energy-law albedo's φ rule over θh rules, an azimuth
//! average of those) multiplies them: without a shared bound a texel whose integrand never
//! converges (a singular BRDF at cos θ = 1e-9) spent 1.9·10⁹ evaluations, minutes, before it
//! reported its error. An entry point runs its work inside [`with_budget`]; every panel of
//! [`integrate`](super::integrate) charges its evaluations to the innermost budget of this
//! thread, and once that is spent every adaptive rule accepts its panels as they are (their
//! error estimates still count, so the result says it missed its tolerance).
//!
//! Determinism: the budget belongs to the thread that runs the work, and the work inside a
//! scope is sequential (no rayon call may run inside one), so where it runs out is a
//! function of the inputs alone.

use std::cell::Cell;

/// Evaluations one integral (one texel, one albedo) may spend: ≈ 2 s at ~100 ns each.
/// Default-tolerance tables use 10² to 10⁵ per texel.
pub const INTEGRAL_EVAL_BUDGET: u64 = 20_000_000;

thread_local! {
    /// Evaluations left in the innermost scope on this thread (`u64::MAX`: none set).
    static LEFT: Cell<u64> = const { Cell::new(u64::MAX) };
}

/// Runs `f` with at most `evals` evaluations (and never more than an enclosing scope has
/// left); charges what it spent to the enclosing scope.
pub fn with_budget<R>(evals: u64, f: impl FnOnce() -> R) -> R {
    let outer = LEFT.with(Cell::get);
    let start = outer.min(evals);
    LEFT.with(|l| l.set(start));
    // restores the enclosing scope's budget even if `f` unwinds
    struct Restore {
        outer: u64,
        start: u64,
    }
    impl Drop for Restore {
        fn drop(&mut self) {
            let spent = self.start - LEFT.with(Cell::get);
            let left = if self.outer == u64::MAX {
                u64::MAX
            } else {
                self.outer - spent
            };
            LEFT.with(|l| l.set(left));
        }
    }
    let _restore = Restore { outer, start };
    f()
}

/// Charges `n` evaluations to the innermost scope (nothing outside one).
#[inline]
pub(crate) fn charge(n: u64) {
    LEFT.with(|l| {
        let v = l.get();
        if v != u64::MAX {
            l.set(v.saturating_sub(n));
        }
    });
}

/// Whether the innermost scope's budget is spent, or the thread's time limit
/// ([`crate::deadline::scoped`]) has passed: either way every rule stops refining. (A run
/// stopped by its time limit is an error and writes nothing, so where that happens never
/// reaches an output.)
#[inline]
pub(crate) fn exhausted() -> bool {
    LEFT.with(Cell::get) == 0 || crate::deadline::current_passed()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nested_scopes_share_and_restore() {
        assert!(!exhausted());
        with_budget(100, || {
            charge(30);
            with_budget(1000, || {
                // bounded by what the outer scope has left
                assert_eq!(LEFT.with(Cell::get), 70);
                charge(70);
                assert!(exhausted());
            });
            assert!(exhausted());
        });
        assert!(!exhausted());
        charge(5); // outside any scope: free
        assert!(!exhausted());
    }

    /// A hopeless integrand stops at the budget, with an error estimate that says so.
    #[test]
    fn adaptive_rule_stops_at_the_budget() {
        use crate::quadrature::{integrate, Tolerance};
        let tol = Tolerance {
            abs: 1e-300,
            max_depth: 60,
            max_evals: u64::MAX,
            ..Default::default()
        };
        let f = |x: f64| [(1.0 / x).sin() / x.sqrt()];
        let e = with_budget(10_000, || integrate(f, 1e-12, 1.0, tol));
        // past the budget, each pending panel of the depth-first recursion (one per level)
        // is still evaluated once
        assert!(e.evals <= 10_000 + 15 * 61, "{}", e.evals);
        assert!(e.error[0] > 1e-6, "{:?}", e.error);
    }
}
