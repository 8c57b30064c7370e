//! One-dimensional nested Clenshaw–Curtis quadrature with the error estimate of the tensor
//! fast path ([`tensor`](crate::hemisphere::tensor)), and its use as the first try of a panel with the
//! adaptive Gauss–Kronrod integrator as the fallback.
//!
//! **Rule.** Clenshaw–Curtis on `2^k + 1` Chebyshev extrema (the nodes and weights of
//! [`tensor::rules`](crate::hemisphere::tensor), Waldvogel 2006): level k's nodes contain level k − 1's,
//! so each level adds `2^(k−1)` evaluations and brings the two coarser results for free.
//! On an integrand analytic in a neighbourhood of the interval the error falls geometrically
//! with the number of nodes, as Gauss–Legendre's does (Trefethen, *Is Gauss quadrature
//! better than Clenshaw–Curtis?*, SIAM Review 50, 2008); with an algebraic singularity
//! `(x − a)^p` at an end it falls like `n^{−2(p+1)}` for both rules.
//!
//! **Estimate.** Per channel `max(|Q_k − Q_{k−1}|, |Q_{k−1} − Q_{k−2}|² / max(|Q_k|, tol))`:
//! the first term is (to first order) the error of the coarser rule Q_{k−1}, an
//! over-estimate of the error of the Q_k that is kept; the second guards against two rules
//! agreeing by coincidence before the asymptotic regime (QUADPACK's estimate guards the same
//! way, Piessens et al. 1983, §2.2.1). Where the estimate does not reach the tolerance by
//! the last level the caller is told (`Err` with the evaluations spent), and
//! [`cc_or_adaptive`] integrates the interval by [`integrate`] instead, counting both.
//!
//! Deterministic: fixed nodes, sums in a fixed order, no state between calls.

// Channel loops index several same-length arrays at once; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

use crate::quadrature::adaptive::{integrate, Estimate, Tolerance};
use crate::quadrature::clenshaw_curtis::{rules, MAX_LEVEL};

/// First level tried: 2^3 + 1 = 9 nodes, compared against 5 and 3.
pub const FIRST_LEVEL: usize = 3;
const NMAX: usize = (1 << MAX_LEVEL) + 1;

/// ∫ₐᵇ f by nested Clenshaw–Curtis levels [`FIRST_LEVEL`]`..=max_level` (at most
/// [`MAX_LEVEL`], 129 nodes), stopping at the first level whose estimate (module docs) is
/// at most `tol` in every channel; `Err(evaluations spent)` if none is, or if a value or
/// estimate is not finite.
pub fn nested_cc<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: &mut F,
    a: f64,
    b: f64,
    tol: f64,
    max_level: usize,
) -> Result<Estimate<N>, u64> {
    nested_cc_from(f, a, b, tol, FIRST_LEVEL, max_level)
}

/// [`nested_cc`] that accepts a level only from `min_level` on (at least
/// [`FIRST_LEVEL`]): the levels below are computed (they are nested in it, so they cost
/// nothing extra) but not accepted, for integrands whose 9-node estimate is not yet in the
/// geometric regime.
pub fn nested_cc_from<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: &mut F,
    a: f64,
    b: f64,
    tol: f64,
    min_level: usize,
    max_level: usize,
) -> Result<Estimate<N>, u64> {
    nested_cc_indexed(&mut |_, x| f(x), a, b, tol, min_level, max_level)
}

/// [`nested_cc_from`] whose integrand is also told each node's index `i` in the finest
/// level (node `x = (a + b)/2 + (b − a)/2·cos(iπ/2^MAX_LEVEL)`, `i < 2^MAX_LEVEL + 1`), so
/// that a caller integrating several functions over the same interval can keep what they
/// share per node.
pub fn nested_cc_indexed<const N: usize, F: FnMut(usize, f64) -> [f64; N]>(
    f: &mut F,
    a: f64,
    b: f64,
    tol: f64,
    min_level: usize,
    max_level: usize,
) -> Result<Estimate<N>, u64> {
    nested_cc_with(f, a, b, tol, min_level, max_level, Estimator::Standard)
}

/// How a nested Clenshaw–Curtis rule estimates the error of the level it keeps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Estimator {
    /// `max(d_k, d_{k−1}²/max(|Q_k|, tol))` with `d_k = |Q_k − Q_{k−1}|`: the error of the
    /// coarser rule, an over-estimate of the kept one's (module docs).
    Standard,
    /// From the second level on (17 nodes), where the differences shrink by a ratio
    /// `r = d_k/d_{k−1} < 1/2`: `max(d_k·r/(1 − r), d_{k−1}²/max(|Q_k|, tol))`. If the errors
    /// fall geometrically by r per level from here, the kept rule's error is the tail
    /// `d_k (r + r² + …) = d_k r/(1 − r)`; for an analytic integrand they fall faster than
    /// that (doubling the nodes roughly squares the error: the kept error is then about
    /// d_k r², a factor 1/r below the estimate), and for an algebraic end behaviour
    /// (x − a)^p they fall by the fixed ratio r = 2^(−2(p+1)) the estimate assumes. Where the
    /// ratio is 1/2 or more (no regime yet), [`Estimator::Standard`]. It stops a level
    /// earlier than the standard estimate on integrands that converge geometrically,
    /// halving the nodes per panel; its reliability on the integrands that use it is
    /// checked against independent references (tests/dielectric_kinds.rs).
    Tail,
}

/// [`nested_cc_indexed`] with the error estimate `estimator`.
pub fn nested_cc_with<const N: usize, F: FnMut(usize, f64) -> [f64; N]>(
    f: &mut F,
    a: f64,
    b: f64,
    tol: f64,
    min_level: usize,
    max_level: usize,
    estimator: Estimator,
) -> Result<Estimate<N>, u64> {
    nested_cc_into(
        &mut |i, x, out: &mut [f64; N]| *out = f(i, x),
        a,
        b,
        tol,
        min_level,
        max_level,
        estimator,
    )
}

/// [`nested_cc_with`] whose integrand writes each node's values into the slot it is given
/// (zeroed before the call) instead of returning them: with many channels (a roughness
/// fibre's 45) the returned arrays were copied at every closure between the integrand and
/// this rule, ~12% of a bake in `memmove`.
pub fn nested_cc_into<const N: usize, F: FnMut(usize, f64, &mut [f64; N])>(
    f: &mut F,
    a: f64,
    b: f64,
    tol: f64,
    min_level: usize,
    max_level: usize,
    estimator: Estimator,
) -> Result<Estimate<N>, u64> {
    let r = rules();
    let max_level = max_level.clamp(FIRST_LEVEL, MAX_LEVEL);
    let min_level = min_level.clamp(FIRST_LEVEL, max_level);
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    // the values at the nodes of the levels computed so far (uninitialized elsewhere: zeroing
    // all 129 × N here cost ~7% of a 45-channel bake in memset, most panels stopping at 9
    // or 17 nodes)
    let mut vals = [const { std::mem::MaybeUninit::<[f64; N]>::uninit() }; NMAX];
    let mut evals = 0u64;
    let mut prev = [[0.0f64; N]; 2];
    for k in FIRST_LEVEL..=max_level {
        let stride = 1usize << (MAX_LEVEL - k);
        // new nodes of level k: odd multiples of its stride (all of them at the first level)
        let mut i = 0;
        while i < NMAX {
            // (i is a multiple of the power of two `stride`: an odd multiple is a new node)
            if k == FIRST_LEVEL || i & stride != 0 {
                f(i, mid + half * r.x[i], vals[i].write([0.0; N]));
                evals += 1;
            }
            i += stride;
        }
        // the rules of levels k, k − 1 and k − 2; the coarser two are the previous levels'
        // (the same sums over the same values, so the same bits), computed only at the first
        let mut q = [[0.0f64; N]; 3];
        let fresh = if k == FIRST_LEVEL { 3 } else { 1 };
        if k > FIRST_LEVEL {
            (q[1], q[2]) = (prev[0], prev[1]);
        }
        for (m, qm) in q.iter_mut().enumerate().take(fresh) {
            let km = k - m;
            let s = 1usize << (MAX_LEVEL - km);
            for (j, &w) in r.w[km].iter().enumerate() {
                // SAFETY: node j·s of level km ≤ k is a node of a level computed above
                // (every level's nodes are the multiples of its stride, and levels
                // FIRST_LEVEL..=k have all been evaluated), so it was written
                let v = unsafe { vals[j * s].assume_init_ref() };
                for c in 0..N {
                    qm[c] += w * v[c];
                }
            }
            for v in qm.iter_mut() {
                *v *= half;
            }
        }
        prev = [q[0], q[1]];
        let mut e = Estimate {
            value: q[0],
            error: [0.0; N],
            evals,
        };
        let mut ok = true;
        for c in 0..N {
            let scale = q[0][c].abs().max(tol);
            let d1 = (q[0][c] - q[1][c]).abs();
            let d2 = (q[1][c] - q[2][c]).abs();
            let guard = d2 * d2 / scale;
            e.error[c] = match estimator {
                Estimator::Tail if k > FIRST_LEVEL && d1 < 0.5 * d2 => {
                    let r = d1 / d2;
                    (d1 * r / (1.0 - r)).max(guard)
                }
                _ => d1.max(guard),
            };
            if !(e.error[c] <= tol && q[0][c].is_finite()) {
                ok = false;
            }
        }
        if ok && k >= min_level {
            return Ok(e);
        }
        if !e.error.iter().all(|x| x.is_finite()) {
            break;
        }
    }
    Err(evals)
}

/// ∫ₐᵇ f to the absolute tolerance `tol.abs`: [`nested_cc`] up to `max_level`, else the
/// adaptive integrator with `tol` from scratch (the evaluations of the abandoned attempt are
/// counted too).
pub fn cc_or_adaptive<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: F,
    a: f64,
    b: f64,
    tol: Tolerance,
    max_level: usize,
) -> Estimate<N> {
    cc_or_adaptive_with(f, a, b, tol, max_level, Estimator::Standard)
}

/// [`cc_or_adaptive`] whose nested rule estimates its error by `estimator`.
pub fn cc_or_adaptive_with<const N: usize, F: FnMut(f64) -> [f64; N]>(
    mut f: F,
    a: f64,
    b: f64,
    tol: Tolerance,
    max_level: usize,
    estimator: Estimator,
) -> Estimate<N> {
    cc_or_adaptive_into(
        |x, out: &mut [f64; N]| *out = f(x),
        a,
        b,
        tol,
        max_level,
        estimator,
    )
}

/// [`cc_or_adaptive_with`] whose integrand writes its values into the slot it is given
/// ([`nested_cc_into`]).
pub fn cc_or_adaptive_into<const N: usize, F: FnMut(f64, &mut [f64; N])>(
    mut f: F,
    a: f64,
    b: f64,
    tol: Tolerance,
    max_level: usize,
    estimator: Estimator,
) -> Estimate<N> {
    if b <= a {
        return Estimate::zero();
    }
    match nested_cc_into(
        &mut |_, x, out: &mut [f64; N]| f(x, out),
        a,
        b,
        tol.abs,
        FIRST_LEVEL,
        max_level,
        estimator,
    ) {
        Ok(e) => e,
        Err(spent) => {
            let mut e = integrate(
                |x| {
                    let mut y = [0.0; N];
                    f(x, &mut y);
                    y
                },
                a,
                b,
                tol,
            );
            e.evals += spent;
            e
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫₀^π sin = 2 (entire: level 4, 17 nodes, is already at rounding), ∫₀¹ √x = 2/3 (an
    /// end singularity p = 1/2: error ~ n^{−3}, not 1e-12 within 129 nodes, so the nested
    /// rule must decline and the fallback reach it), and an estimate that holds.
    #[test]
    fn smooth_converges_singular_falls_back() {
        let pi = std::f64::consts::PI;
        let e = nested_cc(&mut |x: f64| [x.sin()], 0.0, pi, 1e-12, MAX_LEVEL).unwrap();
        assert!((e.value[0] - 2.0).abs() <= 1e-14 + e.error[0], "{e:?}");
        assert!(e.evals <= 33, "{e:?}");
        assert!(nested_cc(&mut |x: f64| [x.sqrt()], 0.0, 1.0, 1e-12, MAX_LEVEL).is_err());
        let tol = Tolerance {
            abs: 1e-12,
            ..Default::default()
        };
        let e = cc_or_adaptive(|x: f64| [x.sqrt()], 0.0, 1.0, tol, MAX_LEVEL);
        assert!((e.value[0] - 2.0 / 3.0).abs() <= 1e-12, "{e:?}");
        assert!(e.evals > 129, "the abandoned attempt is counted: {e:?}");
    }
}
