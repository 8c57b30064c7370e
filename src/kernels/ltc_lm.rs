//! A small deterministic Levenberg–Marquardt solver for the LTC fit (P ≤ 4 parameters).
//!
//! Levenberg 1944, Marquardt 1963: to minimize `E(θ) = Σ r_k(θ)²`, solve
//! `(JᵀJ + λ·diag(JᵀJ)) δ = −Jᵀr` and accept `θ + δ` if it lowers `E` (then λ shrinks),
//! else raise λ and retry. Marquardt's diagonal scaling makes the steps invariant to the
//! parameters' units. Every operation is a fixed sequence of f64 operations on the inputs,
//! so the result depends on nothing but the start point and the residual function.
//!
//! Why LM and not the Nelder–Mead of the reference fitter: the objective is a sum of squares
//! of smooth residuals whose derivatives cost one pass over the nodes (they are written out
//! in `ltc_fit.rs`), so Gauss–Newton steps converge in tens of passes where a simplex
//! method in four dimensions needs hundreds of objective evaluations and stops on a
//! simplex-size criterion, not at a stationary point.

// The normal equations index several same-size arrays at once.
#![allow(clippy::needless_range_loop)]

/// What the residual function gives back: `E = Σ r²`, `g = Jᵀr` and `A = JᵀJ`, accumulated
/// over the residuals by the caller (so no residual vector is stored). `None` for a point
/// outside the parameters' domain.
#[derive(Clone, Copy, Debug)]
pub struct Normal<const P: usize> {
    pub e: f64,
    pub g: [f64; P],
    pub a: [[f64; P]; P],
}

impl<const P: usize> Normal<P> {
    pub fn zero() -> Self {
        Normal {
            e: 0.0,
            g: [0.0; P],
            a: [[0.0; P]; P],
        }
    }

    /// Adds one residual `r` with gradient `j`.
    #[inline]
    pub fn add(&mut self, r: f64, j: &[f64; P]) {
        self.e += r * r;
        for p in 0..P {
            self.g[p] += j[p] * r;
            for q in 0..=p {
                self.a[p][q] += j[p] * j[q];
            }
        }
    }

    /// Mirrors the lower triangle that [`Normal::add`] fills into the upper one.
    pub fn symmetrize(&mut self) {
        for p in 0..P {
            for q in 0..p {
                self.a[q][p] = self.a[p][q];
            }
        }
    }
}

/// Solver settings.
#[derive(Clone, Copy, Debug)]
pub struct LmSettings {
    /// Most residual passes (accepted and rejected steps together).
    pub max_passes: usize,
    /// Stop when an accepted step lowers `E` by less than this fraction of `E`.
    pub rel_decrease: f64,
    /// Initial damping λ.
    pub lambda0: f64,
}

impl Default for LmSettings {
    fn default() -> Self {
        LmSettings {
            max_passes: 80,
            rel_decrease: 1e-7,
            lambda0: 1e-3,
        }
    }
}

/// The result: parameters, `E` there, passes spent.
#[derive(Clone, Copy, Debug)]
pub struct LmResult<const P: usize> {
    pub theta: [f64; P],
    pub e: f64,
    pub passes: usize,
}

/// Solves the P×P system `m x = b` by Gaussian elimination with partial pivoting; `None` if
/// it is singular to working precision.
fn solve<const P: usize>(mut m: [[f64; P]; P], mut b: [f64; P]) -> Option<[f64; P]> {
    for col in 0..P {
        let piv = (col..P).max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))?;
        let pv = m[piv][col].abs();
        if pv.is_nan() || pv == 0.0 {
            return None;
        }
        m.swap(col, piv);
        b.swap(col, piv);
        for row in col + 1..P {
            let f = m[row][col] / m[col][col];
            for k in col..P {
                m[row][k] -= f * m[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; P];
    for row in (0..P).rev() {
        let mut s = b[row];
        for k in row + 1..P {
            s -= m[row][k] * x[k];
        }
        x[row] = s / m[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Minimizes `Σ r²` over the box `[lo, hi]` from `theta0` (projected into the box);
/// `f(θ)` returns the normal equations at θ, or `None` outside the domain (treated as a
/// rejected step). Each trial point is projected onto the box (clamped), the simplest
/// projected Levenberg–Marquardt step (Kanzow, Yamashita & Fukushima 2004); a parameter
/// held at a bound has its gradient component pointing outward removed from the stopping
/// test's predicted decrease, so a minimum on the boundary stops the iteration.
pub fn minimize<const P: usize, F: FnMut(&[f64; P]) -> Option<Normal<P>>>(
    mut f: F,
    theta0: [f64; P],
    (lo, hi): ([f64; P], [f64; P]),
    s: LmSettings,
) -> Option<LmResult<P>> {
    let project = |t: &mut [f64; P]| {
        for p in 0..P {
            t[p] = t[p].clamp(lo[p], hi[p]);
        }
    };
    let mut theta0 = theta0;
    project(&mut theta0);
    let mut theta = theta0;
    let mut cur = f(&theta)?;
    cur.symmetrize();
    let mut passes = 1;
    let mut lambda = s.lambda0;
    while passes < s.max_passes {
        let mut m = cur.a;
        for p in 0..P {
            // Marquardt's scaling, with a floor for a parameter the residuals ignore
            m[p][p] += lambda * cur.a[p][p].max(1e-12 * (1.0 + cur.e));
        }
        let rhs = cur.g.map(|g| -g);
        let Some(delta) = solve(m, rhs) else {
            lambda *= 10.0;
            passes += 1;
            continue;
        };
        // the Gauss–Newton model's decrease, E(θ + δ) ≈ E + 2δᵀg + δᵀAδ: below the
        // stopping fraction, no step can gain more than that (a stationary point)
        let mut pred = 0.0;
        for p in 0..P {
            let mut ad = 0.0;
            for q in 0..P {
                ad += cur.a[p][q] * delta[q];
            }
            pred -= 2.0 * delta[p] * cur.g[p] + delta[p] * ad;
        }
        if pred.is_nan() || pred <= s.rel_decrease * cur.e {
            break;
        }
        let mut trial = theta;
        for p in 0..P {
            trial[p] += delta[p];
        }
        project(&mut trial);
        if trial == theta {
            break;
        }
        passes += 1;
        match f(&trial) {
            Some(mut n) if n.e.is_finite() && n.e < cur.e => {
                n.symmetrize();
                let gain = (cur.e - n.e) / cur.e.max(f64::MIN_POSITIVE);
                theta = trial;
                cur = n;
                lambda = (lambda / 3.0).max(1e-12);
                if gain < s.rel_decrease {
                    break;
                }
            }
            _ => {
                lambda *= 4.0;
                if lambda > 1e12 {
                    break;
                }
            }
        }
    }
    Some(LmResult {
        theta,
        e: cur.e,
        passes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's function as residuals (10(y − x²), 1 − x): the minimum (1, 1) from the
    /// classic start (−1.2, 1).
    #[test]
    fn finds_rosenbrock_minimum() {
        let f = |t: &[f64; 2]| {
            let mut n = Normal::<2>::zero();
            n.add(10.0 * (t[1] - t[0] * t[0]), &[-20.0 * t[0], 10.0]);
            n.add(1.0 - t[0], &[-1.0, 0.0]);
            Some(n)
        };
        let r = minimize(
            f,
            [-1.2, 1.0],
            ([-10.0; 2], [10.0; 2]),
            LmSettings {
                max_passes: 200,
                rel_decrease: 0.0,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(
            (r.theta[0] - 1.0).abs() < 1e-8 && (r.theta[1] - 1.0).abs() < 1e-8,
            "{r:?}"
        );
    }
}
