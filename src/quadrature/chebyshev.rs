//! Piecewise Chebyshev interpolation of smooth functions to a set tolerance.
//!
//! Used where a function is expensive to evaluate (a quadrature of its own) but is needed
//! at millions of points inside another integral: the numerically derived Smith G1 of
//! NDFs without a closed-form Λ. On each panel the function is sampled at 17 Chebyshev–
//! Lobatto points and expanded in Chebyshev polynomials; if the last two coefficients
//! exceed the tolerance the panel is bisected (Trefethen, *Approximation Theory and
//! Approximation Practice*, 2013, ch. 3 and 8: the coefficients of an analytic function
//! decay geometrically, so the tail bounds the truncation error).

const DEG: usize = 16;

/// Most panels one approximation may have (each costs 17 evaluations of a function that is
/// itself a quadrature): a function that will not resolve (noise, a discontinuity) stops
/// being bisected there, and its error estimate says how far it got.
const MAX_PANELS: usize = 4096;

#[derive(Clone, Debug)]
struct Panel {
    a: f64,
    b: f64,
    coef: [f64; DEG + 1],
}

/// A piecewise Chebyshev approximation of a function on `[a, b]`.
#[derive(Clone, Debug)]
pub struct ChebFn {
    panels: Vec<Panel>,
    /// Sum of the tail coefficients over panels: an estimate of the max interpolation error.
    pub error_estimate: f64,
}

impl ChebFn {
    /// Builds the approximation; `tol` bounds the tail-coefficient estimate per panel.
    pub fn build<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, tol: f64) -> ChebFn {
        let mut panels = Vec::new();
        let mut err: f64 = 0.0;
        let mut stack = vec![(a, b, 0u32)];
        // depth-first, left first: panels come out sorted by `a`
        while let Some((lo, hi, depth)) = stack.pop() {
            let coef = fit(&mut f, lo, hi);
            let tail = coef[DEG].abs() + coef[DEG - 1].abs();
            if tail <= tol || depth >= 40 || panels.len() + stack.len() >= MAX_PANELS {
                err = err.max(tail);
                panels.push(Panel { a: lo, b: hi, coef });
            } else {
                let mid = 0.5 * (lo + hi);
                stack.push((mid, hi, depth + 1));
                stack.push((lo, mid, depth + 1));
            }
        }
        ChebFn {
            panels,
            error_estimate: err,
        }
    }

    /// Evaluates by Clenshaw's recurrence on the panel containing `x` (clamped to the domain).
    pub fn eval(&self, x: f64) -> f64 {
        let ps = &self.panels;
        let i = match ps
            .binary_search_by(|p| p.a.partial_cmp(&x).unwrap_or(std::cmp::Ordering::Less))
        {
            Ok(i) => i,
            Err(0) => 0,
            Err(i) => i - 1,
        };
        let p = &ps[i.min(ps.len() - 1)];
        let t = ((2.0 * x - p.a - p.b) / (p.b - p.a)).clamp(-1.0, 1.0);
        clenshaw(&p.coef, t)
    }

    pub fn panel_count(&self) -> usize {
        self.panels.len()
    }
}

/// Chebyshev coefficients of the degree-16 interpolant at Lobatto points.
fn fit<F: FnMut(f64) -> f64>(f: &mut F, a: f64, b: f64) -> [f64; DEG + 1] {
    let n = DEG;
    let mut v = [0.0; DEG + 1];
    for (j, vj) in v.iter_mut().enumerate() {
        let t = (std::f64::consts::PI * j as f64 / n as f64).cos();
        *vj = f(0.5 * (a + b) + 0.5 * (b - a) * t);
    }
    let mut c = [0.0; DEG + 1];
    c.copy_from_slice(&lobatto_coefficients(&v));
    c
}

/// The Chebyshev coefficients `c_k` of the degree-n polynomial through the values `v[j]` at
/// the Lobatto points `t_j = cos(πj/n)`, `n = v.len() − 1 ≥ 1` (the discrete cosine transform
/// of type I; ATAP ch. 3).
pub fn lobatto_coefficients(v: &[f64]) -> Vec<f64> {
    Lobatto::new(v.len() - 1).coefficients(v)
}

/// The transform of [`lobatto_coefficients`] for one degree n, with its cosines
/// `cos(πm/n)`, m = 0..2n, computed once (`cos(πjk/n) = cos(π·(jk mod 2n)/n)`): a line
/// interpolating many channels at once transforms each channel without a cosine call.
pub struct Lobatto {
    n: usize,
    cos: Vec<f64>,
}

impl Lobatto {
    pub fn new(n: usize) -> Lobatto {
        let cos = (0..2 * n)
            .map(|m| (std::f64::consts::PI * m as f64 / n as f64).cos())
            .collect();
        Lobatto { n, cos }
    }

    /// The coefficients of the values `v` (`n + 1` of them).
    pub fn coefficients(&self, v: &[f64]) -> Vec<f64> {
        let n = self.n;
        debug_assert_eq!(v.len(), n + 1);
        (0..=n)
            .map(|k| {
                let mut s = 0.5 * (v[0] + v[n] * self.cos[(n * k) % (2 * n)]);
                for (j, vj) in v.iter().enumerate().take(n).skip(1) {
                    s += vj * self.cos[(j * k) % (2 * n)];
                }
                let scale = if k == 0 || k == n { 1.0 } else { 2.0 };
                s * scale / n as f64
            })
            .collect()
    }

    /// [`Lobatto::coefficients`] of `nc` functions at once: `v[j·nc + c]` is function c at
    /// node j, the result's `[k·nc + c]` its coefficient k. Each function's sum runs in the
    /// same order as in `coefficients`, so the bits agree; the loop over the functions is
    /// the innermost (the compiler vectorizes it), and each cosine is looked up once for
    /// all of them rather than once per function (a grid's line has ~200 channels).
    pub fn coefficients_many(&self, v: &[f64], nc: usize) -> Vec<f64> {
        let n = self.n;
        debug_assert_eq!(v.len(), (n + 1) * nc);
        let mut out = vec![0.0; (n + 1) * nc];
        for (k, row) in out.chunks_exact_mut(nc).enumerate() {
            let cn = self.cos[(n * k) % (2 * n)];
            for ((r, &first), &last) in row.iter_mut().zip(&v[..nc]).zip(&v[n * nc..]) {
                *r = 0.5 * (first + last * cn);
            }
            for j in 1..n {
                let w = self.cos[(j * k) % (2 * n)];
                for (r, &x) in row.iter_mut().zip(&v[j * nc..(j + 1) * nc]) {
                    *r += x * w;
                }
            }
            let scale = if k == 0 || k == n { 1.0 } else { 2.0 };
            for r in row.iter_mut() {
                *r = *r * scale / n as f64;
            }
        }
        out
    }
}

/// `T_0(t) … T_n(t)` into `p` (n + 1 = `p.len()` ≥ 1) by the three-term recurrence (bounded
/// by 1 on [−1, 1], where it is stable), for evaluating many expansions at one point.
pub fn chebyshev_polynomials(t: f64, p: &mut [f64]) {
    p[0] = 1.0;
    if p.len() > 1 {
        p[1] = t;
    }
    for k in 2..p.len() {
        p[k] = 2.0 * t * p[k - 1] - p[k - 2];
    }
}

/// `Σ_k c_k T_k(t)` by Clenshaw's recurrence.
pub fn clenshaw(c: &[f64], t: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for k in (1..c.len()).rev() {
        let b0 = c[k] + 2.0 * t * b1 - b2;
        b2 = b1;
        b1 = b0;
    }
    c[0] + t * b1 - b2
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `coefficients_many` gives each function's `coefficients`, bit for bit.
    #[test]
    fn many_functions_at_once_match_one_at_a_time() {
        for n in [1, 2, 8, 16, 64] {
            let l = Lobatto::new(n);
            let nc = 5;
            let v: Vec<f64> = (0..(n + 1) * nc)
                .map(|i| ((i * 7919) % 113) as f64 / 17.0 - 3.0)
                .collect();
            let many = l.coefficients_many(&v, nc);
            for c in 0..nc {
                let one: Vec<f64> = (0..=n).map(|j| v[j * nc + c]).collect();
                for (k, co) in l.coefficients(&one).into_iter().enumerate() {
                    assert_eq!(
                        co.to_bits(),
                        many[k * nc + c].to_bits(),
                        "n {n} c {c} k {k}"
                    );
                }
            }
        }
    }

    /// exp and a Runge-type function: the achieved max error on a dense grid must be
    /// below the requested 1e-12 (the tail estimate is a heuristic bound; allow 10× it,
    /// i.e. still far below anything the tables need).
    #[test]
    fn approximates_to_tolerance() {
        for f in [|x: f64| x.exp(), |x: f64| 1.0 / (1.0 + 25.0 * x * x)] {
            let c = ChebFn::build(f, -1.0, 1.0, 1e-12);
            let mut worst: f64 = 0.0;
            for i in 0..=10_000 {
                let x = -1.0 + 2.0 * i as f64 / 10_000.0;
                worst = worst.max((c.eval(x) - f(x)).abs());
            }
            assert!(
                worst < 1e-11,
                "max error {worst} with {} panels",
                c.panel_count()
            );
        }
    }
}
