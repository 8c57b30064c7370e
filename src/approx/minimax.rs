//! Discrete linear minimax (Chebyshev) approximation: the coefficients `c` that minimize
//! `max_i |Σ_j Φ_ij c_j − f_i|` over a finite set of points, exactly (to rounding).
//!
//! This is a linear program, solved as its dual by the simplex method — which for this LP is
//! the exchange algorithm of Stiefel (1959; Watson, *Approximation Theory and Numerical
//! Methods*, 1980, ch. 2): a *reference* of n + 1 points with signs σᵢ carries a levelled
//! error h (the residual is σᵢ·h at each of them); the point whose residual exceeds h most
//! enters the reference, and the simplex ratio test says which point leaves so that the
//! dual stays feasible. h rises at every non-degenerate step and the optimum is reached when
//! no residual exceeds h. Unlike the one-dimensional Remez exchange, it needs no Haar
//! condition: it works for any basis in any number of variables (multivariate polynomials,
//! piecewise pieces, products with fixed features).
//!
//! Everything is sequential f64 arithmetic in a fixed order: the same inputs give the same
//! coefficients on any machine and thread count. Weighted minimax (relative error, or any
//! stated weight) is the same problem with the rows divided by their weights.

/// The result of [`solve`].
#[derive(Clone, Debug, PartialEq)]
pub struct Minimax {
    /// The coefficients, one per basis column.
    pub coef: Vec<f64>,
    /// The largest |residual| over all points.
    pub max_error: f64,
    /// The index of the point where it occurs (the first of equals).
    pub argmax: usize,
    /// The levelled error of the final reference: a lower bound of the best possible max
    /// error (de la Vallée Poussin), so `max_error / levelled` measures how close to
    /// optimal the result is (1 at the optimum).
    pub levelled: f64,
    /// Simplex iterations taken.
    pub iterations: usize,
    /// The final reference (point indices), e.g. to warm-start a larger problem.
    pub reference: Vec<usize>,
}

/// Why [`solve`] failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MinimaxError {
    #[error("{points} points cannot determine {unknowns} coefficients")]
    TooFewPoints { points: usize, unknowns: usize },
    #[error("the basis is degenerate on these points (a column is a combination of the others)")]
    Singular,
    #[error("a basis value or target is not finite")]
    NonFinite,
}

/// A dense m × n matrix, row-major: row i holds the basis functions at point i.
#[derive(Clone, Debug)]
pub struct Rows<'a> {
    pub data: &'a [f64],
    pub n: usize,
}

impl Rows<'_> {
    fn m(&self) -> usize {
        self.data.len() / self.n
    }
    fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.n..(i + 1) * self.n]
    }
}

/// Relative slack under which a residual counts as not exceeding the levelled error: the
/// exchange stops when every |residual| ≤ h·(1 + STOP) (1e-9: far below any error a fit
/// states with 3 digits, well above the rounding of n-term sums).
const STOP: f64 = 1e-9;

/// Solves the discrete minimax problem for the basis rows `phi` (m × n) and targets `f`.
/// `start`: a reference to start from (e.g. the one of a coarser grid's solution), else one
/// is chosen by pivoted Gram–Schmidt. At most `max_iter` exchanges (then the best so far,
/// with `levelled < max_error`).
pub fn solve(
    phi: &Rows,
    f: &[f64],
    start: Option<&[usize]>,
    max_iter: usize,
) -> Result<Minimax, MinimaxError> {
    let n = phi.n;
    let m = phi.m();
    assert_eq!(f.len(), m, "one target per row");
    if m < n + 1 {
        return Err(MinimaxError::TooFewPoints {
            points: m,
            unknowns: n,
        });
    }
    if phi.data.iter().chain(f).any(|x| !x.is_finite()) {
        return Err(MinimaxError::NonFinite);
    }
    let mut reference: Vec<usize> = match start {
        Some(s) if s.len() == n + 1 && s.iter().all(|&i| i < m) => s.to_vec(),
        _ => initial_reference(phi)?,
    };
    // signs σᵢ and weights μᵢ ≥ 0 of the dual: M μ = e_{n+1}, M's column k = (σ Φ_k, 1)
    let mut sigma = vec![1.0; n + 1];
    let mut mat = vec![0.0; (n + 1) * (n + 1)];
    let build = |reference: &[usize], sigma: &[f64], mat: &mut [f64]| {
        for (k, &i) in reference.iter().enumerate() {
            for (j, &v) in phi.row(i).iter().enumerate() {
                mat[j * (n + 1) + k] = sigma[k] * v;
            }
            mat[n * (n + 1) + k] = 1.0;
        }
    };
    // the signs of the reference's null vector λ (Φ_Rᵀ λ = 0, λ_last = 1): with σ = sign(λ)
    // the dual is feasible (μ = |λ|/Σ|λ|) and M is non-singular when the null space is a
    // line (M v = 0 gives σ∘v ∥ λ and Σ v = 0)
    let mut at = vec![0.0; n * (n + 1)];
    for (k, &i) in reference.iter().enumerate() {
        for (j, &v) in phi.row(i).iter().enumerate() {
            at[j * (n + 1) + k] = v;
        }
    }
    let lambda = null_vector(&mut at, n).ok_or(MinimaxError::Singular)?;
    for (k, l) in lambda.iter().enumerate() {
        if *l < 0.0 {
            sigma[k] = -1.0;
        }
    }
    let mut e = vec![0.0; n + 1];
    e[n] = 1.0;
    let mut best: Option<Minimax> = None;
    let mut resid = vec![0.0; m];
    for iter in 0..=max_iter {
        build(&reference, &sigma, &mut mat);
        let Some(lu) = Lu::new(&mat, n + 1) else {
            return best.ok_or(MinimaxError::Singular);
        };
        let mu = lu.solve(&e);
        // primal: Mᵀ (c, h) = (σₖ f_k)
        let rhs: Vec<f64> = reference
            .iter()
            .zip(&sigma)
            .map(|(&i, s)| s * f[i])
            .collect();
        let ch = lu.solve_transposed(&rhs);
        let (c, h) = (&ch[..n], ch[n]);
        let (mut jmax, mut rmax) = (0, -1.0);
        for i in 0..m {
            let r = f[i] - dot(phi.row(i), c);
            resid[i] = r;
            if r.abs() > rmax {
                rmax = r.abs();
                jmax = i;
            }
        }
        let cand = Minimax {
            coef: c.to_vec(),
            max_error: rmax,
            argmax: jmax,
            levelled: h.abs(),
            iterations: iter,
            reference: reference.clone(),
        };
        if best.as_ref().is_none_or(|b| cand.max_error < b.max_error) {
            best = Some(cand);
        }
        if rmax <= h.abs() * (1.0 + STOP) + f64::MIN_POSITIVE || iter == max_iter {
            break;
        }
        // entering column a = (σⱼ Φⱼ, 1); ratio test on M d = a
        let sj = resid[jmax].signum();
        let mut a: Vec<f64> = phi.row(jmax).iter().map(|v| sj * v).collect();
        a.push(1.0);
        let d = lu.solve(&a);
        let mut leave = None;
        let mut theta = f64::INFINITY;
        for k in 0..=n {
            if d[k] > 1e-13 {
                let t = mu[k].max(0.0) / d[k];
                if t < theta {
                    theta = t;
                    leave = Some(k);
                }
            }
        }
        let Some(k) = leave else { break };
        reference[k] = jmax;
        sigma[k] = sj;
    }
    Ok(best.expect("at least one iteration"))
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// n + 1 points on which the basis has full rank: n by column-pivoted Gram–Schmidt on the
/// rows (each the point farthest from the span of those chosen), and one more (the point
/// with the largest row norm among the rest), so that the null vector of Φ_Rᵀ exists.
fn initial_reference(phi: &Rows) -> Result<Vec<usize>, MinimaxError> {
    let (m, n) = (phi.m(), phi.n);
    let mut basis: Vec<Vec<f64>> = Vec::with_capacity(n);
    let mut norms: Vec<f64> = (0..m).map(|i| dot(phi.row(i), phi.row(i))).collect();
    let mut rows: Vec<Vec<f64>> = (0..m).map(|i| phi.row(i).to_vec()).collect();
    let mut chosen = Vec::with_capacity(n + 1);
    let scale = norms.iter().cloned().fold(0.0, f64::max);
    for _ in 0..n {
        let (i, &v) = norms
            .iter()
            .enumerate()
            .filter(|(i, _)| !chosen.contains(i))
            .max_by(|a, b| a.1.total_cmp(b.1).then(b.0.cmp(&a.0)))
            .expect("points left");
        if v <= 1e-24 * scale.max(1e-300) {
            return Err(MinimaxError::Singular);
        }
        chosen.push(i);
        let q: Vec<f64> = rows[i].iter().map(|x| x / v.sqrt()).collect();
        for (r, nr) in rows.iter_mut().zip(norms.iter_mut()) {
            let p = dot(r, &q);
            for (x, y) in r.iter_mut().zip(&q) {
                *x -= p * y;
            }
            *nr = dot(r, r);
        }
        basis.push(q);
    }
    let extra = (0..m)
        .filter(|i| !chosen.contains(i))
        .max_by(|&a, &b| {
            dot(phi.row(a), phi.row(a))
                .total_cmp(&dot(phi.row(b), phi.row(b)))
                .then(b.cmp(&a))
        })
        .expect("m > n");
    chosen.push(extra);
    Ok(chosen)
}

/// A null vector of the n × (n + 1) matrix `a` (row-major, overwritten) by Gaussian
/// elimination with complete pivoting; `None` if its rank is below n.
fn null_vector(a: &mut [f64], n: usize) -> Option<Vec<f64>> {
    let w = n + 1;
    let mut cols: Vec<usize> = (0..w).collect();
    let scale = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
    for r in 0..n {
        let (mut pr, mut pc, mut best) = (r, r, -1.0);
        for i in r..n {
            for j in r..w {
                if a[i * w + j].abs() > best {
                    best = a[i * w + j].abs();
                    (pr, pc) = (i, j);
                }
            }
        }
        if best <= 1e-13 * scale {
            return None;
        }
        for j in 0..w {
            a.swap(r * w + j, pr * w + j);
        }
        for i in 0..n {
            a.swap(i * w + r, i * w + pc);
        }
        cols.swap(r, pc);
        let d = a[r * w + r];
        for i in r + 1..n {
            let l = a[i * w + r] / d;
            if l != 0.0 {
                for j in r..w {
                    a[i * w + j] -= l * a[r * w + j];
                }
            }
        }
    }
    // back substitution with the last (free) column's entry 1
    let mut y = vec![0.0; w];
    y[n] = 1.0;
    for r in (0..n).rev() {
        let mut s = a[r * w + n];
        for j in r + 1..n {
            s += a[r * w + j] * y[j];
        }
        y[r] = -s / a[r * w + r];
    }
    let mut x = vec![0.0; w];
    for (k, &c) in cols.iter().enumerate() {
        x[c] = y[k];
    }
    Some(x)
}

/// LU factorization with partial pivoting of a small dense matrix (row-major, k × k).
struct Lu {
    k: usize,
    a: Vec<f64>,
    piv: Vec<usize>,
}

impl Lu {
    fn new(m: &[f64], k: usize) -> Option<Lu> {
        let mut a = m.to_vec();
        let mut piv: Vec<usize> = (0..k).collect();
        let scale = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        for c in 0..k {
            let p = (c..k).max_by(|&x, &y| a[x * k + c].abs().total_cmp(&a[y * k + c].abs()))?;
            if a[p * k + c].abs() <= 1e-14 * scale {
                return None;
            }
            if p != c {
                for j in 0..k {
                    a.swap(p * k + j, c * k + j);
                }
                piv.swap(p, c);
            }
            let d = a[c * k + c];
            for r in c + 1..k {
                let l = a[r * k + c] / d;
                a[r * k + c] = l;
                if l != 0.0 {
                    for j in c + 1..k {
                        a[r * k + j] -= l * a[c * k + j];
                    }
                }
            }
        }
        Some(Lu { k, a, piv })
    }

    /// x with A x = b.
    fn solve(&self, b: &[f64]) -> Vec<f64> {
        let k = self.k;
        let mut x: Vec<f64> = self.piv.iter().map(|&p| b[p]).collect();
        for r in 0..k {
            for c in 0..r {
                x[r] -= self.a[r * k + c] * x[c];
            }
        }
        for r in (0..k).rev() {
            for c in r + 1..k {
                x[r] -= self.a[r * k + c] * x[c];
            }
            x[r] /= self.a[r * k + r];
        }
        x
    }

    /// y with Aᵀ y = b (PA = LU, so Aᵀ = Uᵀ Lᵀ P).
    fn solve_transposed(&self, b: &[f64]) -> Vec<f64> {
        let k = self.k;
        let mut z = b.to_vec();
        for r in 0..k {
            for c in 0..r {
                z[r] -= self.a[c * k + r] * z[c];
            }
            z[r] /= self.a[r * k + r];
        }
        for r in (0..k).rev() {
            for c in r + 1..k {
                z[r] -= self.a[c * k + r] * z[c];
            }
        }
        let mut y = vec![0.0; k];
        for (i, &p) in self.piv.iter().enumerate() {
            y[p] = z[i];
        }
        y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows_1d(xs: &[f64], deg: usize) -> Vec<f64> {
        xs.iter()
            .flat_map(|&x| (0..=deg).map(move |k| x.powi(k as i32)))
            .collect()
    }

    /// Known best lines: x² on [−1, 1] by a + bx is ½ (error ½); eˣ on [0, 1] has slope
    /// e − 1 and equioscillates at 0, ξ = ln(e − 1) and 1, error (2 − e + (e − 1)ξ)/2
    /// (Powell, *Approximation Theory and Methods*, 1981, §7.2).
    #[test]
    fn known_best_lines() {
        let xs: Vec<f64> = (0..=2000).map(|i| -1.0 + i as f64 / 1000.0).collect();
        let phi = rows_1d(&xs, 1);
        let f: Vec<f64> = xs.iter().map(|x| x * x).collect();
        let r = solve(&Rows { data: &phi, n: 2 }, &f, None, 100).unwrap();
        assert!((r.max_error - 0.5).abs() < 1e-12, "{r:?}");
        assert!((r.coef[0] - 0.5).abs() < 1e-12 && r.coef[1].abs() < 1e-12);
        let xs: Vec<f64> = (0..=4000).map(|i| i as f64 / 4000.0).collect();
        let phi = rows_1d(&xs, 1);
        let f: Vec<f64> = xs.iter().map(|x| x.exp()).collect();
        let r = solve(&Rows { data: &phi, n: 2 }, &f, None, 100).unwrap();
        let e = std::f64::consts::E;
        let want = (2.0 - e + (e - 1.0) * (e - 1.0).ln()) / 2.0;
        // ξ lies between grid points: the discrete optimum is within the grid's h²/8·e^ξ
        assert!(
            r.max_error <= want && want - r.max_error < 2e-8,
            "{} vs {want}",
            r.max_error
        );
        assert!((r.coef[1] - (e - 1.0)).abs() < 1e-6);
    }

    /// Chebyshev: the best degree-(n−1) approximation of xⁿ on [−1, 1] leaves 2^{1−n} Tₙ,
    /// error 2^{1−n}; the exchange finds it in any basis, here up to n = 8.
    #[test]
    fn chebyshev_equioscillation() {
        // cos(πi/3360): every extremum cos(kπ/n) of Tₙ, n ≤ 8, is a grid point (lcm 840)
        let xs: Vec<f64> = (0..=3360)
            .map(|i| (std::f64::consts::PI * i as f64 / 3360.0).cos())
            .collect();
        for n in 2..=8 {
            let phi = rows_1d(&xs, n - 1);
            let f: Vec<f64> = xs.iter().map(|x| x.powi(n as i32)).collect();
            let r = solve(&Rows { data: &phi, n }, &f, None, 1000).unwrap();
            let want = 2f64.powi(1 - n as i32);
            assert!(
                (r.max_error - want).abs() < 1e-10 * want.max(1.0),
                "n {n}: {}",
                r.max_error
            );
            assert!(r.levelled <= r.max_error * (1.0 + 1e-8));
        }
    }

    /// Two variables (no Haar condition): the best approximation of x·y² on [−1, 1]² by
    /// {1, x, y, xy} is x/2 (x times the best constant for y², residual ½|x|(2y² − 1)), error
    /// ½; a warm start from the solution's reference takes no exchange.
    #[test]
    fn two_variables_and_warm_start() {
        let g: Vec<f64> = (0..=40).map(|i| -1.0 + i as f64 / 20.0).collect();
        let mut pts = Vec::new();
        for &y in &g {
            for &x in &g {
                pts.push((x, y));
            }
        }
        let phi: Vec<f64> = pts.iter().flat_map(|&(x, y)| [1.0, x, y, x * y]).collect();
        let f: Vec<f64> = pts.iter().map(|&(x, y)| x * y * y).collect();
        let r = solve(&Rows { data: &phi, n: 4 }, &f, None, 1000).unwrap();
        assert!((r.max_error - 0.5).abs() < 1e-12, "{r:?}");
        let again = solve(&Rows { data: &phi, n: 4 }, &f, Some(&r.reference), 1000).unwrap();
        assert_eq!(again.iterations, 0);
        assert!((again.max_error - r.max_error).abs() < 1e-15);
    }

    #[test]
    fn refuses_what_it_cannot_solve() {
        let phi = [1.0, 0.0, 1.0, 0.0, 1.0, 0.0];
        let f = [0.0, 1.0, 2.0];
        assert_eq!(
            solve(&Rows { data: &phi, n: 2 }, &f, None, 10).unwrap_err(),
            MinimaxError::Singular
        );
        assert!(matches!(
            solve(
                &Rows {
                    data: &phi[..4],
                    n: 2
                },
                &f[..2],
                None,
                10
            ),
            Err(MinimaxError::TooFewPoints { .. })
        ));
        let f = [0.0, f64::NAN, 2.0];
        assert_eq!(
            solve(&Rows { data: &phi, n: 2 }, &f, None, 10).unwrap_err(),
            MinimaxError::NonFinite
        );
    }
}
