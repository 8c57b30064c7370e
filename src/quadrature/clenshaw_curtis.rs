//! Clenshaw–Curtis rules on `2^k + 1` Chebyshev extrema, nested level by level (level k's
//! nodes contain level k − 1's), and the level driver of the tensor rules built on them: the
//! dimension with the larger estimated error is refined until the estimate meets the
//! tolerance. Knows nothing of BRDFs; [`crate::hemisphere::tensor`] and the kernels feed it.
//!
//! **Estimate.** Per channel and dimension `max(|Q_k − Q_{k−1}|, |Q_{k−1} − Q_{k−2}|² /
//! max(|Q_k|, tol))`: the first term is (to first order) the error of the coarser rule, an
//! over-estimate of the kept one's under geometric convergence; the second guards against two
//! rules agreeing by coincidence before the asymptotic regime (QUADPACK, Piessens et al.
//! 1983, §2.2.1). Weights by Waldvogel's formula (2006); convergence as Gauss–Legendre's on
//! functions analytic near the interval (Trefethen, *Is Gauss quadrature better than
//! Clenshaw–Curtis?*, SIAM Review 50, 2008).

// Channel loops index several same-length arrays at once; iterator chains would hide that.
#![allow(clippy::needless_range_loop)]

use super::adaptive::Estimate;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Finest level per dimension: 2^7 + 1 = 129 nodes.
pub const MAX_LEVEL: usize = 7;
/// Largest tensor grid tried before giving up (65 × 65 nodes): beyond, the adaptive
/// integrator is cheaper than doubling a whole dimension again.
pub const MAX_NODES: usize = 65 * 65;
/// Starting level per dimension: 2^3 + 1 = 9 nodes (compared against 5).
pub const MIN_LEVEL: usize = 3;
/// Nodes of the finest level.
pub(crate) const NMAX: usize = (1 << MAX_LEVEL) + 1;

/// Clenshaw–Curtis weights on [−1, 1] for every level 0..=MAX_LEVEL, stored for the
/// nodes of the finest level (index i ↔ x = cos(iπ/2^MAX_LEVEL)); a level-k rule uses the
/// indices that are multiples of 2^(MAX_LEVEL − k).
pub(crate) struct Rules {
    pub(crate) x: [f64; NMAX],
    /// w[k][j] = weight of level k's j-th node (j = 0..=2^k).
    pub(crate) w: Vec<Vec<f64>>,
}

/// The Clenshaw–Curtis nodes and weights of every level (shared by every nested rule and
/// kernel that uses them).
pub(crate) fn rules() -> &'static Rules {
    static R: OnceLock<Rules> = OnceLock::new();
    R.get_or_init(|| {
        let mut x = [0.0; NMAX];
        let nm = (NMAX - 1) as f64;
        for (i, xi) in x.iter_mut().enumerate() {
            // symmetric by construction: x[n − i] = −x[i] exactly, x[n/2] = 0
            let j = i.min(NMAX - 1 - i) as f64;
            let v = (PI * j / nm).cos();
            *xi = if 2 * i < NMAX - 1 {
                v
            } else if 2 * i == NMAX - 1 {
                0.0
            } else {
                -v
            };
        }
        let w = (0..=MAX_LEVEL).map(cc_weights).collect();
        Rules { x, w }
    })
}

/// Clenshaw–Curtis weights for n = 2^k intervals (n + 1 nodes x_j = cos(jπ/n)):
/// `w_j = (c_j/n)(1 − Σ_{m=1}^{n/2} b_m cos(2mjπ/n)/(4m² − 1))`, `c_0 = c_n = 1`, else 2,
/// `b_{n/2} = 1`, else 2 (Waldvogel 2006, eq. 2.4; Trefethen 2008, §2). Level 0 is the
/// trapezoid rule.
fn cc_weights(k: usize) -> Vec<f64> {
    let n = 1usize << k;
    if n == 1 {
        return vec![1.0, 1.0];
    }
    let nf = n as f64;
    (0..=n)
        .map(|j| {
            let c = if j == 0 || j == n { 1.0 } else { 2.0 };
            let mut s = 0.0;
            for m in 1..=n / 2 {
                let b = if m == n / 2 { 1.0 } else { 2.0 };
                let mf = m as f64;
                s += b * (2.0 * PI * mf * j as f64 / nf).cos() / (4.0 * mf * mf - 1.0);
            }
            c / nf * (1.0 - s)
        })
        .collect()
}

/// The inner sums of one φ node at u levels ku, ku − 1, ku − 2, times `scale` (the node's
/// inner half-length × outer Jacobian); `vals` is the node's NMAX × N channel-interleaved
/// values, filled at least to level `ku`.
pub(crate) fn inner_sums<const N: usize>(vals: &[f64], scale: f64, ku: usize) -> [[f64; N]; 3] {
    let r = rules();
    let mut out = [[0.0; N]; 3];
    for (m, o) in out.iter_mut().enumerate() {
        let k = ku - m;
        let us = 1usize << (MAX_LEVEL - k);
        for (jj, &wj) in r.w[k].iter().enumerate() {
            let at = jj * us * N;
            for c in 0..N {
                o[c] += wj * vals[at + c];
            }
        }
        for v in o.iter_mut() {
            *v *= scale;
        }
    }
    out
}

/// The nested level driver of the tensor rules (the hemisphere's fast path and the V-groove
/// pieces): starting from level [`MIN_LEVEL`] in both
/// dimensions, `fill(sc, evals, i, ku)` brings φ node `i`'s inner values to u level `ku`
/// (counting new evaluations) and `inner(sc, i, ku)` returns its inner sums at u levels
/// ku, ku − 1, ku − 2 (times the node's scale); the dimension with the larger estimated
/// error is refined until the estimate meets `tol`, or `Err(evaluations)` once
/// [`MAX_LEVEL`] / [`MAX_NODES`] is reached or the estimate is not finite.
pub(crate) fn refine<const N: usize, S>(
    sc: &mut S,
    tol: f64,
    mut fill: impl FnMut(&mut S, &mut u64, usize, usize),
    mut inner: impl FnMut(&mut S, usize, usize) -> [[f64; N]; 3],
) -> Result<Estimate<N>, u64> {
    let r = rules();
    let mut evals = 0u64;
    // Q(kp − a, ku − b) for (a, b) in (0,0), (1,0), (2,0), (0,1), (0,2): the φ rule of level
    // kp − a uses the φ indices that are multiples of 2^(MAX_LEVEL − kp + a).
    let mut quads = |sc: &mut S, kp: usize, ku: usize| -> [[f64; N]; 5] {
        let mut q = [[0.0; N]; 5];
        let ps = 1usize << (MAX_LEVEL - kp);
        for (ii, &wi) in r.w[kp].iter().enumerate() {
            let i = ii * ps;
            let s3 = inner(sc, i, ku);
            for c in 0..N {
                q[0][c] += wi * s3[0][c];
                q[3][c] += wi * s3[1][c];
                q[4][c] += wi * s3[2][c];
            }
            for a in 1..=2 {
                if ii % (1 << a) == 0 {
                    let w = r.w[kp - a][ii >> a];
                    for c in 0..N {
                        q[a][c] += w * s3[0][c];
                    }
                }
            }
        }
        q
    };

    let (mut kp, mut ku) = (MIN_LEVEL, MIN_LEVEL);
    let grid = |kp: usize| (0..NMAX).step_by(1usize << (MAX_LEVEL - kp));
    for i in grid(kp) {
        fill(sc, &mut evals, i, ku);
    }
    loop {
        let [q, qp1, qp2, qu1, qu2] = quads(&mut *sc, kp, ku);
        // Per dimension, the error of the kept level is estimated by the last difference
        // |Q_k − Q_{k−1}| (the error of the coarser rule), but never below what the
        // difference before predicts if convergence were only quadratic in that relative
        // error, |Q_{k−1} − Q_{k−2}|²/scale: two rules can agree by coincidence before the
        // asymptotic regime (QUADPACK's estimate guards the same way, Piessens et al. 1983,
        // §2.2.1). The scale is the channel's magnitude, at least the tolerance.
        let mut err = [0.0; N];
        let (mut ep, mut eu) = (0.0f64, 0.0f64);
        for c in 0..N {
            let a = nested_error(q[c], qp1[c], qp2[c], tol);
            let b = nested_error(q[c], qu1[c], qu2[c], tol);
            ep = ep.max(a);
            eu = eu.max(b);
            err[c] = a + b;
        }
        if !(ep.is_finite() && eu.is_finite()) {
            return Err(evals);
        }
        // (a NaN value can hide behind a finite estimate: `max` ignores NaN)
        if err.iter().all(|&e| e <= tol) && q.iter().all(|v| v.is_finite()) {
            return Ok(Estimate {
                value: q,
                error: err,
                evals,
            });
        }
        let (can_p, can_u) = (kp < MAX_LEVEL, ku < MAX_LEVEL);
        if !(can_p || can_u) {
            return Err(evals);
        }
        if if ep >= eu { can_p } else { !can_u } {
            kp += 1;
        } else {
            ku += 1;
        }
        if ((1usize << kp) + 1) * ((1usize << ku) + 1) > MAX_NODES {
            return Err(evals);
        }
        for i in grid(kp) {
            fill(sc, &mut evals, i, ku);
        }
    }
}

/// The error estimate of nested rules' level k from its results `q` (level k), `q1` (k − 1)
/// and `q2` (k − 2): `max(|q − q1|, |q1 − q2|²/max(|q|, tol))` — the last difference, but
/// never below what the difference before predicts under quadratic convergence (see
/// the comment in `refine`; QUADPACK, Piessens et al. 1983, §2.2.1). Shared by the nested
/// Clenshaw–Curtis rules that use this module's levels.
pub(crate) fn nested_error(q: f64, q1: f64, q2: f64, tol: f64) -> f64 {
    let d = |x: f64, y: f64| (x - y).abs();
    d(q, q1).max(d(q1, q2).powi(2) / q.abs().max(tol))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clenshaw–Curtis on n + 1 points integrates polynomials of degree ≤ n exactly; the
    /// only error is rounding of ≤ 129 terms of size ≤ 1: bounded by 1e-14.
    #[test]
    fn clenshaw_curtis_is_exact_on_polynomials() {
        let r = rules();
        for k in 1..=MAX_LEVEL {
            let n = 1usize << k;
            let stride = 1usize << (MAX_LEVEL - k);
            for deg in 0..=n as i32 {
                let q: f64 = (0..=n).map(|j| r.w[k][j] * r.x[j * stride].powi(deg)).sum();
                let exact = if deg % 2 == 0 {
                    2.0 / (deg as f64 + 1.0)
                } else {
                    0.0
                };
                assert!((q - exact).abs() < 1e-14, "level {k} degree {deg}: {q}");
            }
        }
    }
}
