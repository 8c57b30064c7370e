//! A smooth, expensive function at the points of one table line (a row of texels), by
//! adaptive Chebyshev interpolation of values computed at fewer points.
//!
//! **Why.** Along a row of a split-sum table (one roughness, every view μ) the integrals are
//! analytic functions of `x = √μ` on the texels' range (the substitution absorbs the
//! square-root behaviour of the view direction near grazing). A 128-texel row of GGX's split
//! sum is resolved to 1e-7 by 33–65 Chebyshev nodes; computing those nodes (at a tighter
//! tolerance) and interpolating costs ~0.7 of 128 quadratures, and ~0.3 of 512.
//!
//! **Method.** On an interval the function is sampled at the Chebyshev–Lobatto points of
//! degree n = 8, 16, 32, 64 (nested: raising the degree keeps every value; a caller may start
//! the doubling at another degree, [`line_batched`]) and expanded in
//! Chebyshev polynomials (Trefethen, *Approximation Theory and Approximation Practice*, SIAM
//! 2013, ch. 3). The coefficients of an analytic function decay geometrically, so the last
//! two, `|c_{n−1}| + |c_n|`, estimate what truncation leaves out (ATAP ch. 8; the test of
//! [`chebyshev`](crate::quadrature::chebyshev)), and interpolation aliases the omitted coefficients onto
//! the kept ones, which at most doubles the error (ATAP Theorem 4.2: `‖f − p_n‖ ≤
//! 2 Σ_{k>n} |a_k|`): the truncation estimate is `tail = 2(|c_{n−1}| + |c_n|)`. (Without the
//! factor two, a row of GGX's split sum at α = 0.0067 came out 4.3e-8 off at μ = 0.035
//! with an estimate of 3.8e-8: the test `dfg_lines::lines_match_texel_values` caught it.)
//! The sampled values carry their own quadrature error δ, which the interpolant passes on
//! amplified at most by the Lebesgue constant `Λ_n ≤ (2/π) ln(n + 1) + 1` (ATAP Theorem
//! 15.2: 3.66 at n = 64). An interval is accepted when `tail + Λ_n·δ_max + rounding ≤ tol`,
//! and that sum is each of its texels' error estimate. Nodes are computed at `tol/4` (their
//! estimates are usually well below what they were asked for); where `Λ_n·δ` alone exceeds
//! `tol/2` the interval's nodes are recomputed at an 8× tighter tolerance (twice at most,
//! while that costs fewer quadratures than its texels), and then its texels are computed
//! directly. (At 512², 13,315 texels of filament-dfg's narrow rows went direct without the
//! recomputation, 640 with it: 27.9 → 14.6 M evaluations.)
//!
//! **Adaptivity and cost.** An interval whose degree-64 interpolant does not pass is halved
//! (each half starts again at degree 8). An interval holding no more texels than the nodes
//! its next step would need is not interpolated: its texels are computed one by one at the
//! caller's tolerance, exactly as without this module — so a function that is not smooth
//! (or a line too short to pay) gets the direct values.
//!
//! **Determinism.** One line is processed sequentially in a fixed order and every value is
//! a pure function of its coordinates; lines are independent, so a caller may run them in
//! parallel without changing a bit.

use crate::quadrature::chebyshev::{chebyshev_polynomials, clenshaw, Lobatto};

/// What this module does, for the sidecar's `quadrature.method`.
pub const METHOD: &str = "adaptive Chebyshev interpolation along a line of texels (src/quadrature/interp1d.rs): Chebyshev-Lobatto nodes of degree 8, 16, 32, 64 (nested; the lines whose functions need ~24 start there: 24, 48), intervals halved where the last degree does not pass; accepted where 2(|c_(n-1)| + |c_n|) + Lebesgue(n) * (largest node error) <= tolerance and 3 extra samples between the nodes agree; that sum is each texel's estimate; nodes at tolerance/4 (recomputed 8x and 64x tighter where their errors use up half the tolerance); intervals with no more texels than nodes computed texel by texel.";

/// Lowest and highest interpolation degree on one interval.
pub const MIN_DEG: usize = 8;
pub const MAX_DEG: usize = 64;
/// Requested tolerance of the interpolation nodes, as a fraction of the line's tolerance.
pub const NODE_TOL_FRACTION: f64 = 1.0 / 4.0;
/// Relative rounding error allowed for the coefficient transform and the evaluation (~10³
/// floating-point operations of relative error 1.1e-16, rounded up).
const ROUNDING: f64 = 1e-13;
/// Factor by which an interval's node tolerance is tightened where the nodes' errors use up
/// the budget, and the most it is tightened in all.
const TIGHTEN: f64 = 8.0;
const TIGHTEN_MAX: f64 = 64.0;
/// Halvings after which an interval's texels are computed directly whatever their number.
const MAX_DEPTH: u32 = 20;

/// Bound on the Lebesgue constant of the degree-n Chebyshev–Lobatto points (ATAP Thm 15.2).
pub fn lebesgue(n: usize) -> f64 {
    2.0 / std::f64::consts::PI * ((n + 1) as f64).ln() + 1.0
}

/// The function at one point: per-channel values and error bounds, and the integrand
/// evaluations spent.
#[derive(Clone, Debug)]
pub struct Sample {
    pub value: Vec<f64>,
    pub error: Vec<f64>,
    pub evals: u64,
}

/// The function at every point of the line.
#[derive(Clone, Debug, Default)]
pub struct LineValues {
    /// `value[i·nc + c]`: channel c at xs\[i\].
    pub value: Vec<f64>,
    /// Error estimates, laid out as `value`.
    pub error: Vec<f64>,
    /// Integrand evaluations of every sample.
    pub evals: u64,
    /// Interpolation nodes computed, texels computed directly.
    pub nodes: usize,
    pub direct: usize,
}

/// Where the sample test of an accepted degree-n interpolant looks (in t ∈ [−1, 1]): halfway
/// (in angle) between the two outermost nodes at each end, where a polynomial that misses a
/// feature near an end swings most, and one interior point that no degree's nodes hit.
fn sample_points(n: usize) -> [f64; 3] {
    let e = (std::f64::consts::PI / (2 * n) as f64).cos();
    [e, -e, 0.137_036]
}

/// What became of one interval.
enum Outcome {
    /// Accepted: per channel, the Chebyshev coefficients and the error estimate.
    Interpolated(Vec<(Vec<f64>, f64)>),
    /// Split in two (the halves are on the stack).
    Halved,
    /// Its texels are computed one by one.
    Direct,
}

/// Lobatto node j of degree n on [a, b]: `t_j = cos(πj/n)`, node 0 at b, node n at a.
fn node(a: f64, b: f64, j: usize, n: usize) -> f64 {
    if j == 0 {
        b
    } else if j == n {
        a
    } else {
        0.5 * (a + b) + 0.5 * (b - a) * (std::f64::consts::PI * (j as f64 / n as f64)).cos()
    }
}

/// A function at the points `xs` (strictly increasing) with `nc` channels, to tolerance
/// `tol` (see the module docs). `node_fn(x, t)` returns it at x within t (called with
/// `t = tol/4` at interpolation nodes and sample-test points, all inside
/// `[xs[0], xs[last]]`); `texel(i, t)` returns it at xs\[i\] (called with `t = tol` where
/// texels are computed directly; a caller may use its exact texel coordinates there). `breaks` (increasing) cut the line into the first
/// intervals: where the function varies fast on one side of a point, the other side is not
/// made to pay for it.
pub fn line<N, T>(
    xs: &[f64],
    breaks: &[f64],
    nc: usize,
    tol: f64,
    node_fn: N,
    texel: T,
) -> LineValues
where
    N: FnMut(f64, f64) -> Sample,
    T: FnMut(usize, f64) -> Sample,
{
    line_with_node_tol(
        MIN_DEG,
        xs,
        breaks,
        nc,
        tol,
        tol * NODE_TOL_FRACTION,
        node_fn,
        texel,
    )
}

/// [`line()`] with the nodes computed at `node_tol` instead of `tol/4`, and each interval's
/// degrees starting at `first` (see [`line_batched`]; [`MIN_DEG`] in `line`): for a function
/// whose node estimates come close to what they were asked for, `Λ_n·δ` at tol/4 can exceed
/// the `tol/2` beyond which an interval is computed directly (Λ_8 = 2.4, Λ_64 = 3.66); at
/// `tol/8` it stays below `0.46·tol` for every degree.
#[allow(clippy::too_many_arguments)]
pub fn line_with_node_tol<N, T>(
    first: usize,
    xs: &[f64],
    breaks: &[f64],
    nc: usize,
    tol: f64,
    node_tol: f64,
    mut node_fn: N,
    mut texel: T,
) -> LineValues
where
    N: FnMut(f64, f64) -> Sample,
    T: FnMut(usize, f64) -> Sample,
{
    line_batched(
        first,
        xs,
        breaks,
        nc,
        tol,
        node_tol,
        |ps, t| ps.iter().map(|&x| node_fn(x, t)).collect(),
        |is, t| is.iter().map(|&i| texel(i, t)).collect(),
    )
}

/// [`line_with_node_tol`] with the samples asked for in batches: `nodes(ps, t)` returns the
/// function at every point of `ps` (the new nodes of one degree, or one interval's
/// sample-test points), `direct(is, t)` at every texel index of `is` (one interval's direct
/// texels), in order. A caller whose samples are expensive may compute a batch in parallel;
/// as each sample is a pure function of its point, the line's values do not depend on how.
///
/// Each interval's degrees start at `first` (2 ≤ first ≤ [`MAX_DEG`]; then 2·first,
/// 4·first, … up to [`MAX_DEG`]); callers pass [`MIN_DEG`] unless their functions are known
/// to need more, whose low degrees it then skips (a function that needs 24 costs 25 nodes
/// from 24, 33 from 8: 8 and 16 fail, 32 passes).
#[allow(clippy::too_many_arguments)]
pub fn line_batched<N, T>(
    first: usize,
    xs: &[f64],
    breaks: &[f64],
    nc: usize,
    tol: f64,
    node_tol: f64,
    mut nodes: N,
    mut direct: T,
) -> LineValues
where
    N: FnMut(&[f64], f64) -> Vec<Sample>,
    T: FnMut(&[usize], f64) -> Vec<Sample>,
{
    let nx = xs.len();
    let mut out = LineValues {
        value: vec![0.0; nx * nc],
        error: vec![0.0; nx * nc],
        ..Default::default()
    };
    if nx == 0 {
        return out;
    }
    // intervals (a, b, first texel, end texel, depth) on a stack, processed left to right;
    // the initial ones are the line cut at `breaks`
    let mut cuts = vec![(xs[0], 0usize)];
    for &c in breaks {
        let k = xs.partition_point(|&x| x < c);
        if c > cuts[cuts.len() - 1].0 && k < nx {
            cuts.push((c, k));
        }
    }
    cuts.push((xs[nx - 1], nx));
    let mut stack: Vec<(f64, f64, usize, usize, u32)> = cuts
        .windows(2)
        .rev()
        .map(|w| (w[0].0, w[1].0, w[0].1, w[1].1, 0))
        .collect();
    while let Some((a, b, i0, i1, depth)) = stack.pop() {
        let texels = i1 - i0;
        if texels == 0 {
            continue;
        }
        let mut n = first.clamp(2, MAX_DEG);
        let mut vals: Vec<Sample> = Vec::new();
        // the nodes' tolerance on this interval: tightened (and the nodes recomputed) where
        // their own errors use up the budget
        let mut ntol = node_tol;
        let outcome = loop {
            if texels <= n + 1 || depth >= MAX_DEPTH {
                break Outcome::Direct;
            }
            // the degree-n values, reusing the degree-n/2 ones at even indices
            let old = std::mem::take(&mut vals);
            let fresh = |j: usize| old.is_empty() || j % 2 == 1;
            let ps: Vec<f64> = (0..=n)
                .filter(|&j| fresh(j))
                .map(|j| node(a, b, j, n))
                .collect();
            let mut new = nodes(&ps, ntol).into_iter();
            out.nodes += ps.len();
            vals = (0..=n)
                .map(|j| {
                    if fresh(j) {
                        let s = new.next().expect("one sample per node");
                        out.evals += s.evals;
                        s
                    } else {
                        old[j / 2].clone()
                    }
                })
                .collect();
            let (mut pass, mut floor_all) = (true, 0.0f64);
            let mut fit = Vec::with_capacity(nc);
            // every channel's coefficients in one pass (k-major: `all[k·nc + c]`)
            let node_major: Vec<f64> = vals.iter().flat_map(|s| s.value.iter().copied()).collect();
            let all = Lobatto::new(n).coefficients_many(&node_major, nc);
            for c in 0..nc {
                let delta = vals.iter().map(|s| s.error[c]).fold(0.0, f64::max);
                let scale = vals.iter().map(|s| s.value[c].abs()).fold(0.0, f64::max);
                let co: Vec<f64> = all.iter().skip(c).step_by(nc).copied().collect();
                let tail = 2.0 * (co[n].abs() + co[n - 1].abs());
                let floor = lebesgue(n) * delta + ROUNDING * scale;
                let err = tail + floor;
                pass &= err <= tol;
                floor_all = if floor.is_finite() {
                    floor_all.max(floor)
                } else {
                    f64::INFINITY
                };
                fit.push((co, err));
            }
            if pass {
                // the tail test can be fooled by a function whose coefficients dip before
                // they decay (or by a feature between the nodes): check the interpolant at
                // points between nodes before accepting it (the "sample test" of
                // Aurentz & Trefethen, "Chopping a Chebyshev series", ACM TOMS 43, 2017, §3)
                let mut ok = true;
                let ts = sample_points(n);
                let ps = ts.map(|t| 0.5 * (a + b) + 0.5 * (b - a) * t);
                let got = nodes(&ps, ntol);
                out.nodes += ps.len();
                for (t, s) in ts.into_iter().zip(got) {
                    out.evals += s.evals;
                    for (c, (co, err)) in fit.iter().enumerate() {
                        // both sides' errors: the interpolant's estimate and the sample's
                        ok &= (clenshaw(co, t) - s.value[c]).abs() <= err + s.error[c];
                    }
                }
                if ok {
                    break Outcome::Interpolated(fit);
                }
            }
            if floor_all > 0.5 * tol {
                // the nodes' own errors use up the budget: refining the degree cannot help.
                // Nodes computed to a tighter tolerance usually can (a quadrature whose
                // estimate came close to what it was asked for), up to TIGHTEN_MAX times
                // while that costs fewer quadratures than the texels; then the texels
                // are computed directly.
                if ntol > node_tol / TIGHTEN_MAX && 2 * (n + 1) < texels {
                    ntol /= TIGHTEN;
                    vals.clear();
                    continue;
                }
                break Outcome::Direct;
            }
            if 2 * n > MAX_DEG || 2 * n + 1 >= texels {
                // halve the interval instead (both halves start again at the first degree)
                let m = 0.5 * (a + b);
                let k = i0 + xs[i0..i1].partition_point(|&x| x < m);
                if k == i0 || k == i1 {
                    break Outcome::Direct;
                }
                stack.push((m, b, k, i1, depth + 1));
                stack.push((a, m, i0, k, depth + 1));
                break Outcome::Halved;
            }
            n *= 2;
        };
        match outcome {
            Outcome::Halved => {}
            Outcome::Interpolated(fit) => {
                // value(texel, c) = Σ_k T_k(t)·co_c[k]: with the coefficients k-major, each
                // k adds one multiple of a contiguous row to the texel's channels (a loop the
                // compiler vectorizes; a line across a 512² table has ~900 channels)
                let deg = fit[0].0.len();
                let mut km = vec![0.0; deg * nc];
                for (c, (co, _)) in fit.iter().enumerate() {
                    for (k, &v) in co.iter().enumerate() {
                        km[k * nc + c] = v;
                    }
                }
                let mut tk = vec![0.0; deg];
                for (i, &x) in xs.iter().enumerate().take(i1).skip(i0) {
                    let t = if b > a {
                        ((2.0 * x - a - b) / (b - a)).clamp(-1.0, 1.0)
                    } else {
                        0.0
                    };
                    chebyshev_polynomials(t, &mut tk);
                    let row = &mut out.value[i * nc..(i + 1) * nc];
                    row.copy_from_slice(&km[..nc]);
                    for (k, &w) in tk.iter().enumerate().skip(1) {
                        for (r, &v) in row.iter_mut().zip(&km[k * nc..(k + 1) * nc]) {
                            *r += w * v;
                        }
                    }
                    for (c, (_, err)) in fit.iter().enumerate() {
                        out.error[i * nc + c] = *err;
                    }
                }
            }
            Outcome::Direct => {
                let is: Vec<usize> = (i0..i1).collect();
                for (i, s) in is.iter().copied().zip(direct(&is, tol)) {
                    out.evals += s.evals;
                    out.direct += 1;
                    for c in 0..nc {
                        out.value[i * nc + c] = s.value[c];
                        out.error[i * nc + c] = s.error[c];
                    }
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn exact(v: f64) -> Sample {
        Sample {
            value: vec![v],
            error: vec![0.0],
            evals: 1,
        }
    }

    fn pts(n: usize) -> Vec<f64> {
        (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect()
    }

    /// An analytic function with a pole at distance 0.02 from the line (forces halving): every
    /// point must be within its own estimate, and fewer samples than points must be taken.
    #[test]
    fn interpolates_within_estimate() {
        let f = |x: f64| (1.0 + x).ln() / (x + 0.02) + (7.0 * x).sin();
        let xs = pts(2000);
        let g = line(
            &xs,
            &[],
            1,
            1e-9,
            |x, _| exact(f(x)),
            |i, _| exact(f(xs[i])),
        );
        assert!(g.nodes > 65, "the pole must force halving");
        assert!(g.evals < 400, "{} samples", g.evals);
        for (i, &x) in xs.iter().enumerate() {
            let e = (g.value[i] - f(x)).abs();
            // values up to ~50: rounding of the evaluation ~1e-14 on top of the estimate
            assert!(
                e <= g.error[i] + 1e-13,
                "x {x}: error {e:e} > estimate {:e}",
                g.error[i]
            );
            assert!(g.error[i] <= 1e-9);
        }
    }

    /// Started at degree 24, a line whose function needs ~20 (poles at ±1.25i: Bernstein
    /// ρ = 1.25 + √(1 + 1.25²) ≈ 2.85, |c_n| ~ ρ^−n below 1e-9 from n ≈ 20) takes fewer
    /// samples than from 8 (9, 17, 33 nodes), and every point is within its estimate.
    #[test]
    fn a_later_first_degree_skips_the_low_ones() {
        let f = |x: f64| 1.0 / (1.0 + 0.64 * x * x);
        let xs: Vec<f64> = pts(2000).iter().map(|x| 2.0 * x - 1.0).collect();
        let run = |first: usize| {
            line_batched(
                first,
                &xs,
                &[],
                1,
                1e-9,
                1e-9 * NODE_TOL_FRACTION,
                |ps, _| ps.iter().map(|&x| exact(f(x))).collect(),
                |is, _| is.iter().map(|&i| exact(f(xs[i]))).collect(),
            )
        };
        let (from8, from24) = (run(MIN_DEG), run(24));
        assert_eq!(from8.nodes, 33 + 3);
        assert_eq!(from24.nodes, 25 + 3);
        for g in [&from8, &from24] {
            assert_eq!(g.direct, 0);
            for (i, &x) in xs.iter().enumerate() {
                let e = (g.value[i] - f(x)).abs();
                // values ≤ 1: rounding ~1e-15 on top of the estimate
                assert!(e <= g.error[i] + 1e-14, "x {x}: {e:e} > {:e}", g.error[i]);
                assert!(g.error[i] <= 1e-9);
            }
        }
    }

    /// A kink never resolves: the texels next to it end up computed directly, exactly.
    #[test]
    fn kinks_fall_back_to_direct_values() {
        let f = |x: f64| (x - 0.37).abs() + x * x;
        let xs = pts(1000);
        let g = line(
            &xs,
            &[],
            1,
            1e-9,
            |x, _| exact(f(x)),
            |i, _| exact(f(xs[i])),
        );
        assert!(g.direct > 0 && g.direct < 200, "{} direct", g.direct);
        for (i, &x) in xs.iter().enumerate() {
            assert!((g.value[i] - f(x)).abs() <= g.error[i] + 1e-15, "x {x}");
        }
    }

    /// A break in front of a boundary layer (√(x + 10⁻³) near 0) keeps the smooth side
    /// cheap: fewer samples than without it, every point still within its estimate, and no
    /// interval crosses the break (the interpolant's texels on each side come from their own
    /// side's nodes only).
    #[test]
    fn breaks_cut_the_line() {
        let f = |x: f64| (x + 1e-3).sqrt();
        let xs = pts(1000);
        let plain = line(
            &xs,
            &[],
            1,
            1e-9,
            |x, _| exact(f(x)),
            |i, _| exact(f(xs[i])),
        );
        let seen = std::cell::RefCell::new(Vec::new());
        let cut = line(
            &xs,
            &[0.02],
            1,
            1e-9,
            |x, _| {
                seen.borrow_mut().push(x);
                exact(f(x))
            },
            |i, _| exact(f(xs[i])),
        );
        assert!(cut.evals < plain.evals, "{} vs {}", cut.evals, plain.evals);
        assert!(
            seen.borrow().contains(&0.02),
            "0.02 must be an interval end"
        );
        for (i, &x) in xs.iter().enumerate() {
            assert!((cut.value[i] - f(x)).abs() <= cut.error[i] + 1e-15, "x {x}");
        }
    }

    /// Sample errors are passed on: a node error δ gives estimates ≥ Λ·δ; a line too short
    /// to pay is computed directly.
    #[test]
    fn sample_errors_and_short_lines() {
        let xs = pts(100);
        let g = line(
            &xs,
            &[],
            2,
            1e-6,
            |x, t| Sample {
                value: vec![x, x * x],
                error: vec![t, 0.0],
                evals: 1,
            },
            |_, _| unreachable!("a quadratic is resolved at degree 8"),
        );
        assert_eq!(g.direct, 0);
        for i in 0..xs.len() {
            assert!(g.error[2 * i] >= lebesgue(MIN_DEG) * 1e-6 * NODE_TOL_FRACTION);
            assert!(g.error[2 * i + 1] < 1e-12);
        }
        let short = pts(9);
        let g = line(
            &short,
            &[],
            1,
            1e-6,
            |_, _| unreachable!(),
            |i, _| exact(short[i]),
        );
        assert_eq!(g.direct, 9);
    }
}
