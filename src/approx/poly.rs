//! Multivariate polynomials on [−1, 1]ⁿ: which monomials a polynomial has (its *support*),
//! the Chebyshev basis the minimax solver fits in, the monomial coefficients the emitted
//! code evaluates, and the nested Horner scheme that evaluates them.
//!
//! A support is *downward closed*: with t^e it holds every t^f, f ≤ e componentwise. The
//! products of Chebyshev polynomials T_e = Π_v T_{e_v}(t_v) over a downward-closed support
//! span exactly the monomials t^e over it (T_k has the powers k, k − 2, …), so a fit is made
//! in the well-conditioned Chebyshev basis and converted exactly to monomials for Horner.
//!
//! Nested Horner: p(t₁, …) = Σᵢ t₁ⁱ pᵢ(t₂, …) is evaluated as
//! `(((p_d)·t₁ + p_{d−1})·t₁ + …)·t₁ + p₀`, each pᵢ the same way in the remaining variables:
//! one fused multiply-add per step, so a polynomial of k coefficients costs at most k − 1
//! operations ([`Support::horner_cost`]).

/// The exponents of a polynomial's monomials in lexicographic order: downward closed
/// ([`Support::from_exponents`]), or sparse but closed under lowering one exponent by two
/// ([`Support::sparse`]) — either way the span of its Chebyshev products is the span of its
/// monomials, so a fit in the one basis converts exactly to the other.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Support {
    nvars: usize,
    exps: Vec<Vec<u8>>,
}

impl Support {
    /// All monomials of total degree ≤ `d` in `nvars` variables.
    pub fn total_degree(nvars: usize, d: usize) -> Support {
        let mut exps = Vec::new();
        let mut e = vec![0u8; nvars];
        loop {
            if e.iter().map(|&x| x as usize).sum::<usize>() <= d {
                exps.push(e.clone());
            }
            // odometer, last variable fastest
            let mut k = nvars;
            loop {
                if k == 0 {
                    return Support::from_exponents(nvars, exps).expect("downward closed");
                }
                k -= 1;
                if (e[k] as usize) < d {
                    e[k] += 1;
                    for x in &mut e[k + 1..] {
                        *x = 0;
                    }
                    break;
                }
            }
        }
    }

    /// A support from exponent tuples (any order, duplicates removed); `None` if it is empty,
    /// a tuple has the wrong length, or the set is not downward closed.
    pub fn from_exponents(nvars: usize, mut exps: Vec<Vec<u8>>) -> Option<Support> {
        exps.sort();
        exps.dedup();
        if exps.is_empty() || exps.iter().any(|e| e.len() != nvars) {
            return None;
        }
        for e in &exps {
            for v in 0..nvars {
                if e[v] > 0 {
                    let mut f = e.clone();
                    f[v] -= 1;
                    if exps.binary_search(&f).is_err() {
                        return None;
                    }
                }
            }
        }
        Some(Support { nvars, exps })
    }

    /// A sparse support: the constant and any monomials, provided that lowering one
    /// exponent ≥ 2 by two stays in the set (T_k(x) holds x^k, x^(k−2), …: the Chebyshev
    /// products then span exactly these monomials). `None` if it is empty, lacks the
    /// constant, a tuple has the wrong length, or that closure fails. For cheap forms whose
    /// terms a shader can share: {1, r², e, e·r} needs no r term.
    pub fn sparse(nvars: usize, mut exps: Vec<Vec<u8>>) -> Option<Support> {
        exps.sort();
        exps.dedup();
        if exps.is_empty() || exps.iter().any(|e| e.len() != nvars) {
            return None;
        }
        if exps.binary_search(&vec![0u8; nvars]).is_err() {
            return None;
        }
        for e in &exps {
            for v in 0..nvars {
                if e[v] >= 2 {
                    let mut f = e.clone();
                    f[v] -= 2;
                    if exps.binary_search(&f).is_err() {
                        return None;
                    }
                }
            }
        }
        Some(Support { nvars, exps })
    }

    /// Every downward-closed support in `nvars` variables whose exponents are at most
    /// `max_degree` in total and whose Horner cost is at most `max_cost` (small searches:
    /// the cheapest fits).
    pub fn all_closed(nvars: usize, max_degree: usize, max_cost: usize) -> Vec<Support> {
        let cand = Support::total_degree(nvars, max_degree).exps;
        let mut out: Vec<Support> = Vec::new();
        // grow sets one monomial at a time, keeping closedness (breadth first, deduplicated)
        let mut frontier = vec![vec![vec![0u8; nvars]]];
        while let Some(set) = frontier.pop() {
            let s = Support::from_exponents(nvars, set.clone()).expect("closed");
            if s.horner_cost() > max_cost || out.contains(&s) {
                continue;
            }
            out.push(s);
            for e in &cand {
                if set.contains(e) {
                    continue;
                }
                let mut next = set.clone();
                next.push(e.clone());
                if let Some(n) = Support::from_exponents(nvars, next) {
                    frontier.push(n.exps);
                }
            }
        }
        out.sort_by(|a, b| {
            (a.horner_cost(), a.len(), &a.exps).cmp(&(b.horner_cost(), b.len(), &b.exps))
        });
        out
    }

    pub fn nvars(&self) -> usize {
        self.nvars
    }

    pub fn len(&self) -> usize {
        self.exps.len()
    }

    pub fn is_empty(&self) -> bool {
        self.exps.is_empty()
    }

    pub fn exponents(&self) -> &[Vec<u8>] {
        &self.exps
    }

    /// The largest exponent of each variable.
    pub fn max_exponents(&self) -> Vec<usize> {
        (0..self.nvars)
            .map(|v| self.exps.iter().map(|e| e[v] as usize).max().unwrap_or(0))
            .collect()
    }

    /// The total degree.
    pub fn degree(&self) -> usize {
        self.exps
            .iter()
            .map(|e| e.iter().map(|&x| x as usize).sum::<usize>())
            .max()
            .unwrap_or(0)
    }

    /// Operations of the nested Horner scheme (each a multiply or a fused multiply-add).
    pub fn horner_cost(&self) -> usize {
        fn cost(exps: &[&[u8]]) -> usize {
            if exps.is_empty() || exps[0].is_empty() {
                return 0;
            }
            let d = exps.iter().map(|e| e[0]).max().unwrap_or(0) as usize;
            let mut c = d;
            for i in 0..=d {
                let sub: Vec<&[u8]> = exps
                    .iter()
                    .filter(|e| e[0] as usize == i)
                    .map(|e| &e[1..])
                    .collect();
                c += cost(&sub);
            }
            c
        }
        let refs: Vec<&[u8]> = self.exps.iter().map(|e| e.as_slice()).collect();
        cost(&refs)
    }

    /// The Chebyshev basis at `t` (one value per variable, in [−1, 1]): Π_v T_{e_v}(t_v) for
    /// every exponent, in order, into `out`.
    pub fn chebyshev_row(&self, t: &[f64], out: &mut [f64]) {
        let maxe = self.max_exponents();
        let tk: Vec<Vec<f64>> = t
            .iter()
            .zip(&maxe)
            .map(|(&x, &d)| chebyshev_values(x, d))
            .collect();
        for (o, e) in out.iter_mut().zip(&self.exps) {
            *o = e
                .iter()
                .enumerate()
                .map(|(v, &k)| tk[v][k as usize])
                .product();
        }
    }

    /// The monomial coefficients (of t^e, in order) of the polynomial with Chebyshev
    /// coefficients `cheb` (of T_e, in order).
    pub fn to_monomial(&self, cheb: &[f64]) -> Vec<f64> {
        let d = self.max_exponents().into_iter().max().unwrap_or(0);
        let a = chebyshev_monomials(d);
        let mut out = vec![0.0; self.len()];
        for (c, f) in cheb.iter().zip(&self.exps) {
            // T_f = Π_v Σ_j a[f_v][j] t_v^j, j ≤ f_v of f_v's parity: every such e is in
            // the support (closed, or sparse: closed under lowering by two)
            for (k, e) in self.exps.iter().enumerate() {
                let w: f64 = e
                    .iter()
                    .zip(f)
                    .map(|(&ev, &fv)| a[fv as usize][ev as usize])
                    .product();
                out[k] += c * w;
            }
        }
        out
    }

    /// Evaluates the monomial coefficients `coef` at `t` by the nested Horner scheme, in f64.
    pub fn horner(&self, coef: &[f64], t: &[f64]) -> f64 {
        fn rec(exps: &[(&[u8], f64)], t: &[f64]) -> f64 {
            if exps.is_empty() {
                return 0.0;
            }
            if exps[0].0.is_empty() {
                return exps.iter().map(|e| e.1).sum();
            }
            let d = exps.iter().map(|e| e.0[0]).max().unwrap_or(0) as usize;
            let part = |i: usize| {
                let sub: Vec<(&[u8], f64)> = exps
                    .iter()
                    .filter(|e| e.0[0] as usize == i)
                    .map(|e| (&e.0[1..], e.1))
                    .collect();
                rec(&sub, &t[1..])
            };
            let mut acc = part(d);
            for i in (0..d).rev() {
                acc = acc * t[0] + part(i);
            }
            acc
        }
        let pairs: Vec<(&[u8], f64)> = self
            .exps
            .iter()
            .map(|e| e.as_slice())
            .zip(coef.iter().copied())
            .collect();
        rec(&pairs, t)
    }

    /// A bound on |Σ_e c_e t^e| · (steps of rounding) for |t| ≤ 1: the sum of |coef| times
    /// `2·(degree + 1)` — each coefficient passes through at most `degree` Horner steps of two
    /// roundings each (multiply, add) and one rounding of its own. Multiplied by the unit
    /// roundoff it bounds the rounding error of the Horner evaluation (Higham, *Accuracy and
    /// Stability of Numerical Algorithms*, 2002, §5.1: |p̂ − p| ≤ γ_{2d} Σ|c_e||t|^e).
    pub fn rounding_weight(&self, coef: &[f64]) -> f64 {
        let d = self.degree() as f64;
        coef.iter().map(|c| c.abs()).sum::<f64>() * (2.0 * d + 2.0)
    }

    /// A bound on |∂p/∂t_v| over [−1, 1]ⁿ summed over the variables: Σ_e |c_e|·Σ_v e_v.
    /// Times the largest error of a computed variable it bounds the error that error adds.
    pub fn derivative_weight(&self, coef: &[f64]) -> f64 {
        self.exps
            .iter()
            .zip(coef)
            .map(|(e, c)| c.abs() * e.iter().map(|&x| x as f64).sum::<f64>())
            .sum()
    }
}

/// T_0(x), …, T_d(x).
fn chebyshev_values(x: f64, d: usize) -> Vec<f64> {
    let mut v = vec![1.0; d + 1];
    if d >= 1 {
        v[1] = x;
    }
    for k in 2..=d {
        v[k] = 2.0 * x * v[k - 1] - v[k - 2];
    }
    v
}

/// a[k][j]: the coefficient of x^j in T_k(x), k ≤ d.
fn chebyshev_monomials(d: usize) -> Vec<Vec<f64>> {
    let mut a = vec![vec![0.0; d + 1]; d + 1];
    a[0][0] = 1.0;
    if d >= 1 {
        a[1][1] = 1.0;
    }
    for k in 2..=d {
        for j in 0..=k {
            let up = if j >= 1 { 2.0 * a[k - 1][j - 1] } else { 0.0 };
            a[k][j] = up - a[k - 2][j];
        }
    }
    a
}

#[cfg(test)]
mod tests {

    /// A sparse support: the constant and monomials closed under lowering by two; its
    /// Chebyshev coefficients convert exactly to monomial ones (the same polynomial).
    #[test]
    fn sparse_supports_convert_exactly() {
        let s = Support::sparse(2, vec![vec![0, 0], vec![0, 2], vec![1, 1], vec![2, 0]]).unwrap();
        assert_eq!(s.len(), 4);
        assert!(Support::from_exponents(2, s.exponents().to_vec()).is_none());
        let cheb = [0.3, -1.2, 0.7, 2.5];
        let mono = s.to_monomial(&cheb);
        for t in [[0.1, -0.4], [0.9, 0.2], [-0.7, 0.65]] {
            let mut row = vec![0.0; s.len()];
            s.chebyshev_row(&t, &mut row);
            let direct: f64 = row.iter().zip(&cheb).map(|(a, b)| a * b).sum();
            assert!((s.horner(&mono, &t) - direct).abs() < 1e-12, "{t:?}");
        }
        // no constant; x³ without x; a wrong tuple length
        assert!(Support::sparse(2, vec![vec![1, 0]]).is_none());
        assert!(Support::sparse(2, vec![vec![0, 0], vec![3, 0]]).is_none());
        assert!(Support::sparse(2, vec![vec![0, 0], vec![1]]).is_none());
    }
    use super::*;

    #[test]
    fn supports_and_costs() {
        let s = Support::total_degree(2, 2);
        assert_eq!(s.len(), 6);
        assert_eq!(s.horner_cost(), 5);
        assert_eq!(Support::total_degree(3, 4).len(), 35);
        assert_eq!(Support::total_degree(3, 4).horner_cost(), 34);
        assert_eq!(Support::total_degree(1, 7).horner_cost(), 7);
        // {1, x, y, xy, y²}: p0(y) = c + cy + cy² (2), p1(y) = c + cy (1), outer 1
        let s = Support::from_exponents(
            2,
            vec![vec![0, 0], vec![1, 0], vec![0, 1], vec![1, 1], vec![0, 2]],
        )
        .unwrap();
        assert_eq!(s.horner_cost(), 4);
        assert!(Support::from_exponents(2, vec![vec![0, 0], vec![1, 1]]).is_none());
        let all = Support::all_closed(2, 3, 5);
        assert!(all.iter().all(|s| s.horner_cost() <= 5));
        assert_eq!(all[0].len(), 1);
        // the 23 closed sets of degree ≤ 3 and cost ≤ 5 (counted by hand and by brute force)
        assert_eq!(all.len(), 23);
    }

    /// The monomial form agrees with the Chebyshev form everywhere, and Horner with the
    /// plain sum of monomials.
    #[test]
    fn chebyshev_to_monomial_and_horner() {
        let s = Support::total_degree(2, 6);
        let cheb: Vec<f64> = (0..s.len())
            .map(|k| ((k * 37 % 11) as f64 - 5.0) / 7.0)
            .collect();
        let mono = s.to_monomial(&cheb);
        let mut row = vec![0.0; s.len()];
        for &t in &[[-1.0, 1.0], [0.3, -0.7], [0.99, 0.01], [0.0, 0.0]] {
            s.chebyshev_row(&t, &mut row);
            let via_cheb: f64 = row.iter().zip(&cheb).map(|(a, b)| a * b).sum();
            let plain: f64 = s
                .exponents()
                .iter()
                .zip(&mono)
                .map(|(e, c)| c * t[0].powi(e[0] as i32) * t[1].powi(e[1] as i32))
                .sum();
            assert!((via_cheb - plain).abs() < 1e-12, "{via_cheb} {plain}");
            assert!((s.horner(&mono, &t) - plain).abs() < 1e-12);
        }
    }
}
