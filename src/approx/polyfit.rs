//! Minimax polynomials on point sets: global (one polynomial over the whole set) and
//! piecewise (one per cell of a uniform grid of cells), in variables already mapped to
//! [−1, 1] (global) or [0, 1] (piecewise). The coefficients returned are monomial and
//! rounded to f32 — what emitted code holds — and the errors are those of the rounded
//! coefficients, evaluated as the code evaluates them (nested Horner).
//!
//! Large sets are solved coarse to fine: the exchange first runs on every k-th point, and
//! its final reference starts the exchange on the whole set (it is a feasible basis there
//! too), which then needs only the few exchanges the finer set adds.

use super::minimax::{self, MinimaxError, Rows};
use super::poly::Support;

/// A fitted polynomial.
#[derive(Clone, Debug, PartialEq)]
pub struct PolyFit {
    pub support: Support,
    /// Monomial coefficients (in the support's order), f32 values.
    pub coef: Vec<f64>,
    /// max |weight·(p − f)| over the points, with the f32 coefficients.
    pub max_error: f64,
    pub argmax: usize,
}

/// Exchange iterations allowed per solve (a degree-12 bivariate fit takes a few hundred).
const MAX_ITER: usize = 20_000;

/// Points above which the exchange first runs on a subset.
const COARSE_ABOVE: usize = 6000;

/// The minimax polynomial over `support` of the targets `f` at the points `t` (`t[i]` holds
/// point i's variables, each in [−1, 1]); `weight[i]` divides point i's error (relative
/// error: |f|), none for absolute error.
pub fn fit(
    support: &Support,
    t: &[Vec<f64>],
    f: &[f64],
    weight: Option<&[f64]>,
) -> Result<PolyFit, MinimaxError> {
    let n = support.len();
    let m = t.len();
    let w = |i: usize| weight.map_or(1.0, |w| w[i]);
    let mut rows = vec![0.0; m * n];
    for (i, ti) in t.iter().enumerate() {
        support.chebyshev_row(ti, &mut rows[i * n..(i + 1) * n]);
        let wi = w(i);
        for x in &mut rows[i * n..(i + 1) * n] {
            *x /= wi;
        }
    }
    let g: Vec<f64> = (0..m).map(|i| f[i] / w(i)).collect();
    let mut start = None;
    if m > COARSE_ABOVE && m / 8 > 4 * n {
        let step = (m / COARSE_ABOVE.max(16 * n)).max(2);
        let idx: Vec<usize> = (0..m).step_by(step).collect();
        let sub: Vec<f64> = idx
            .iter()
            .flat_map(|&i| rows[i * n..(i + 1) * n].iter().copied())
            .collect();
        let gs: Vec<f64> = idx.iter().map(|&i| g[i]).collect();
        if let Ok(r) = minimax::solve(&Rows { data: &sub, n }, &gs, None, MAX_ITER) {
            start = Some(r.reference.iter().map(|&k| idx[k]).collect::<Vec<_>>());
        }
    }
    let r = minimax::solve(&Rows { data: &rows, n }, &g, start.as_deref(), MAX_ITER)?;
    let coef: Vec<f64> = support
        .to_monomial(&r.coef)
        .into_iter()
        .map(|c| c as f32 as f64)
        .collect();
    let (mut max_error, mut argmax) = (0.0, 0);
    for i in 0..m {
        let e = ((support.horner(&coef, &t[i]) - f[i]) / w(i)).abs();
        if e > max_error {
            max_error = e;
            argmax = i;
        }
    }
    Ok(PolyFit {
        support: support.clone(),
        coef,
        max_error,
        argmax,
    })
}

/// A piecewise polynomial: `cells[v]` uniform cells along variable v over [0, 1]; cell
/// (i₀, i₁, …) is numbered i₀ + cells₀·(i₁ + cells₁·…) and holds one polynomial in the
/// local variables 2(x_v·cells_v − i_v) − 1 ∈ [−1, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseFit {
    pub cells: Vec<usize>,
    pub support: Support,
    /// Per cell, the monomial coefficients (f32 values).
    pub coef: Vec<Vec<f64>>,
    pub max_error: f64,
    pub argmax: usize,
}

/// The cell of each variable of a point x ∈ [0, 1]ⁿ, as the emitted code finds it:
/// `min(int(x·cells), cells − 1)` in f32.
pub fn cell_of(x: &[f64], cells: &[usize]) -> Vec<usize> {
    x.iter()
        .zip(cells)
        .map(|(&v, &k)| (((v as f32) * k as f32).max(0.0) as usize).min(k - 1))
        .collect()
}

fn cell_number(idx: &[usize], cells: &[usize]) -> usize {
    idx.iter()
        .zip(cells)
        .rev()
        .fold(0, |acc, (&i, &k)| acc * k + i)
}

/// The local variables of x in cell `idx`.
pub fn local(x: &[f64], idx: &[usize], cells: &[usize]) -> Vec<f64> {
    x.iter()
        .zip(idx.iter().zip(cells))
        .map(|(&v, (&i, &k))| 2.0 * (v * k as f64 - i as f64) - 1.0)
        .collect()
}

/// Fits one polynomial per cell, each on the points of its cell and of a margin of
/// `margin` (in [0, 1] units) around it, so that a point on a cell border is fitted by
/// whichever cell the f32 arithmetic of the code sends it to. The error is measured at every
/// point in the cell [`cell_of`] gives it.
pub fn fit_piecewise(
    support: &Support,
    cells: &[usize],
    x: &[Vec<f64>],
    f: &[f64],
    weight: Option<&[f64]>,
    margin: f64,
) -> Result<PiecewiseFit, MinimaxError> {
    let ncell: usize = cells.iter().product();
    let w = |i: usize| weight.map_or(1.0, |w| w[i]);
    let mut coef = Vec::with_capacity(ncell);
    for c in 0..ncell {
        let mut idx = Vec::with_capacity(cells.len());
        let mut rest = c;
        for &k in cells {
            idx.push(rest % k);
            rest /= k;
        }
        let members: Vec<usize> = (0..x.len())
            .filter(|&i| {
                x[i].iter()
                    .zip(idx.iter().zip(cells))
                    .all(|(&v, (&j, &k))| {
                        let lo = j as f64 / k as f64 - margin;
                        let hi = (j + 1) as f64 / k as f64 + margin;
                        v >= lo && v <= hi
                    })
            })
            .collect();
        if members.len() < support.len() + 1 {
            // an empty or nearly empty cell (a domain that does not fill the box)
            if members.is_empty() {
                coef.push(vec![0.0; support.len()]);
                continue;
            }
            return Err(MinimaxError::TooFewPoints {
                points: members.len(),
                unknowns: support.len(),
            });
        }
        let t: Vec<Vec<f64>> = members.iter().map(|&i| local(&x[i], &idx, cells)).collect();
        let g: Vec<f64> = members.iter().map(|&i| f[i]).collect();
        let ws: Vec<f64> = members.iter().map(|&i| w(i)).collect();
        let p = fit(support, &t, &g, weight.map(|_| ws.as_slice()))?;
        coef.push(p.coef);
    }
    let (mut max_error, mut argmax) = (0.0, 0);
    for i in 0..x.len() {
        let idx = cell_of(&x[i], cells);
        let c = cell_number(&idx, cells);
        let e = ((support.horner(&coef[c], &local(&x[i], &idx, cells)) - f[i]) / w(i)).abs();
        if e > max_error {
            max_error = e;
            argmax = i;
        }
    }
    Ok(PiecewiseFit {
        cells: cells.to_vec(),
        support: support.clone(),
        coef,
        max_error,
        argmax,
    })
}

/// The x in [a, b] minimizing `g` by golden-section search to within `tol` (g unimodal; at
/// worst a local minimum). Deterministic: the same evaluations in the same order.
pub fn golden_min(mut g: impl FnMut(f64) -> f64, a: f64, b: f64, tol: f64) -> (f64, f64) {
    let r = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (a, b);
    let mut c = b - r * (b - a);
    let mut d = a + r * (b - a);
    let (mut gc, mut gd) = (g(c), g(d));
    while (b - a).abs() > tol {
        if gc <= gd {
            b = d;
            d = c;
            gd = gc;
            c = b - r * (b - a);
            gc = g(c);
        } else {
            a = c;
            c = d;
            gc = gd;
            d = a + r * (b - a);
            gd = g(d);
        }
    }
    if gc <= gd {
        (c, gc)
    } else {
        (d, gd)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid2(n: usize) -> Vec<Vec<f64>> {
        let mut v = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                v.push(vec![i as f64 / n as f64, j as f64 / n as f64]);
            }
        }
        v
    }

    /// A polynomial in the support is reproduced (to f32 coefficients); the coarse-to-fine
    /// path gives the same optimum as the direct one.
    #[test]
    fn reproduces_polynomials_and_coarse_to_fine_agrees() {
        let s = Support::total_degree(2, 3);
        let x = grid2(100);
        let t: Vec<Vec<f64>> = x
            .iter()
            .map(|p| vec![2.0 * p[0] - 1.0, 2.0 * p[1] - 1.0])
            .collect();
        let f: Vec<f64> = t
            .iter()
            .map(|p| 0.5 + p[0] * p[1] - 0.25 * p[1].powi(3))
            .collect();
        let r = fit(&s, &t, &f, None).unwrap();
        assert!(r.max_error < 1e-7, "{}", r.max_error);
        let g: Vec<f64> = t.iter().map(|p| (p[0] + 2.0 * p[1]).exp()).collect();
        let big = fit(&s, &t, &g, None).unwrap();
        assert!(t.len() > COARSE_ABOVE);
        let direct = {
            let n = s.len();
            let mut rows = vec![0.0; t.len() * n];
            for (i, ti) in t.iter().enumerate() {
                s.chebyshev_row(ti, &mut rows[i * n..(i + 1) * n]);
            }
            minimax::solve(&Rows { data: &rows, n }, &g, None, MAX_ITER).unwrap()
        };
        // the same LP optimum (the f32 rounding of the coefficients aside)
        assert!((big.max_error - direct.max_error).abs() < 1e-5 * direct.max_error.max(1e-3));
    }

    /// Piecewise: a function with a kink along x = 1/2 is fitted exactly by two linear
    /// pieces split there, and badly by one.
    #[test]
    fn piecewise_follows_a_kink() {
        let s = Support::total_degree(2, 1);
        let x = grid2(64);
        let f: Vec<f64> = x.iter().map(|p| (p[0] - 0.5).abs() + 0.1 * p[1]).collect();
        let one = fit_piecewise(&s, &[1, 1], &x, &f, None, 0.0).unwrap();
        let two = fit_piecewise(&s, &[2, 1], &x, &f, None, 0.0).unwrap();
        assert!(one.max_error > 0.1);
        assert!(two.max_error < 1e-6, "{}", two.max_error);
    }

    #[test]
    fn golden_section() {
        let (x, g) = golden_min(|x| (x - 0.3).powi(2) + 1.0, 0.0, 1.0, 1e-6);
        assert!((x - 0.3).abs() < 1e-6 && (g - 1.0).abs() < 1e-12);
    }
}
