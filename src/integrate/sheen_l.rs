//! The cloth albedo `∫ D_Charlie(α) V_Ashikhmin (n·l) dω_l` in light-direction coordinates:
//! a 1D integral over `μl = n·l` of 1D integrals over the relative azimuth φ, for narrow
//! sheen lobes (the rows of a dfg table that are expensive in half-vector coordinates).
//!
//! **The integrand.** With Charlie `D = norm·(sin²θh)^k`, `norm = (2 + 1/α)/(2π)`,
//! `k = 1/(2α)` (Estevez & Kulla 2017, "Production Friendly Microfacet Sheen BRDF", eq. 2)
//! and Ashikhmin's visibility `V = 1/(4(μl + μv − μl μv))` (Neubelt & Pettineo 2013,
//! "Crafting a Next-Gen Material Pipeline for The Order: 1886", as used by Filament), V does
//! not depend on φ, and since `cos θh = (μv + μl)/|v + l|`, `|v + l|² = 2 + 2 v·l`,
//! `v·l = μv μl + sv sl cos φ` (sv = sin θv, sl = sin θl):
//!
//! `sin²θh = (P − B x)/(A − B x)`, `x = sin²(φ/2)`, `A = 2 + 2(μv μl + sv sl)`,
//! `B = 4 sv sl`, `P = A − (μv + μl)²`,
//!
//! so `B_cloth(μv) = ∫₀¹ dμl norm·μl·V·s0^k·J(μl)`, `s0 = P/A = sin²((θv + θl)/2)` (φ = 0),
//! `J = ∫_{−π}^{π} (sin²θh/s0)^k dφ` (the l-space form of the hemisphere integral,
//! `dω_l = dμl dφ`).
//!
//! **Inner rule (φ).** `ln(sin²θh/s0) = ln(1 − (B/P)x) − ln(1 − (B/A)x)` is concave in x
//! (second derivative `−B²/(P − Bx)² + B²/(A − Bx)² ≤ 0` as `P ≤ A`) with slope `−γ/k`
//! at x = 0, `γ = k·B(μv + μl)²/(PA)`, so the integrand is at most `exp(−γx)`: a peak at
//! φ = 0 of width ~`√(2/γ)`. Where `γ > T` (T = 40, `e^{−T} ≈ 4e-18`) φ is cut at
//! `x_c = T/γ` (the rest is bounded by `2(π − φ_c)e^{−T}` and added to the error) and the
//! trapezoid rule on `[−φ_c, φ_c]` integrates a function negligible with all its
//! derivatives at both ends (geometric convergence, as on the real line: Trefethen &
//! Weideman 2014, "The exponentially convergent trapezoidal rule", SIAM Review 56, §5).
//! Otherwise the integrand is periodic and the trapezoid rule runs over the whole circle, in
//! the variable t of the Möbius map `tan((π − φ)/2) = ρ tan(t/2)`, `ρ = min(1, √k(μv + μl)/2)`,
//! which keeps the rule periodic and puts nodes into the dip of width ~`(μv + μl)√k` at φ = π
//! (where l is opposite v near the horizon and h passes the normal); there
//! `x = C/(C + ρ²S)`, `dφ/dt = ρ/(C + ρ²S)`, `C = cos²(t/2)`, `S = sin²(t/2)`. Both rules
//! are nested (halving the step) and stop when `|T_m − T_{m/2}|` (the error of the coarser
//! rule) times the node's outer weight is below `tol/20`, or below 1e-14 of `T_m` (rounding);
//! that difference (plus the cut-off bound and 1e-15 of the value for rounding) is the
//! node's error bound.
//!
//! **Outer rule (μl).** The integrand peaks at the horizon (μl → 0: `s0` is largest at θl =
//! π/2, decaying like `exp(−k(κε + ε²/(2(1 + sv))))` in `ε = π/2 − θl`, `κ = μv/(1 + sv)`)
//! with the visibility's layer `μl/(μl + μv)` of width μv; `μl = a sinh z`, `a` the smaller
//! of the two widths, resolves both (features of width O(1) in z), from 0 to `μ_cut`, beyond
//! which `s0^k·norm·π/2 < tol/1000` (`V μl ≤ 1/4`, `J ≤ 2π`, s0 decreasing in μl; the
//! bound is added to the error). Nested Clenshaw–Curtis levels (9 … 129 nodes) with the
//! estimate of [`tensor`](super::tensor): `max(|Q_k − Q_{k−1}|, |Q_{k−1} − Q_{k−2}|²/max(|Q_k|,
//! tol))`, plus the inner rules' error bounds summed with the outer weights, plus the two
//! cut-off bounds; `Err(evaluations)` if that does not reach `tol` (absolute) within 129
//! outer nodes, 1025 inner nodes per outer node or [`EVAL_CAP`] evaluations.
//!
//! Determinism: fixed nodes and summation order; nothing is shared between calls.

// Node loops index several same-length arrays at once.
#![allow(clippy::needless_range_loop)]

use super::adaptive::Estimate;
use super::dfg_kernel::{exp_poly, ln_poly, sin_cos_poly};
use super::tensor::{rules as cc_rules, MAX_LEVEL};
use std::f64::consts::PI;
use std::sync::OnceLock;

const NMAX: usize = (1 << MAX_LEVEL) + 1;
/// Cut-off exponent of the inner rule: the integrand beyond φ_c is below e^{−T}.
const T_CUT: f64 = 40.0;
/// Finest inner rule: 2^10 intervals on [0, φ_c] (1025 nodes). Grazing views with grazing
/// light directions (μv, μl ≲ 0.02) need more than 257 (the coarser levels are the same
/// nodes, so texels that converge there give the same bits): with 257 the path gave up on
/// most texels at μv < 0.017 for α ≥ 10⁻³, which then cost ~25,000 generic-path evaluations
/// each (~20% of filament-dfg's CPU at 512²).
const M_MAX: usize = 1024;
/// Inner nodes evaluated per batch ([`Batch::eval`]): small enough that its stack arrays
/// cost nothing to set up (at M_MAX/2 + 1 = 513 they were zeroed, 8 KB, on every batch,
/// ~4% of filament-dfg's CPU at 512²), large enough for the loops to vectorize.
const CHUNK: usize = 64;
/// Lobes this path takes: α < 1/16, i.e. k = 1/(2α) > 8. For wider lobes `(sin θh)^{1/α}`
/// is not smooth enough where h passes the normal (φ = π, θl = θv) for the inner rule, and
/// the half-vector kernels share their work across a table column anyway.
pub const MAX_ALPHA: f64 = 1.0 / 16.0;
/// Evaluations after which a texel gives up. The fallbacks (the half-vector kernel, then
/// the generic path) cost more per evaluation and give up at grazing views too: the grazing
/// texels that converge here take up to ~25,000 (μv = 0.004, α = 0.02).
pub const EVAL_CAP: u64 = 30000;

/// What this path does, for documentation and the benchmarks.
pub const METHOD: &str = "cloth in light-direction coordinates (src/integrate/sheen_l.rs): nested Clenshaw-Curtis over mu_l = a sinh z (a = min(mu_v, lobe width at the horizon)), inner trapezoid rule over phi (cut at exp(-40) of the peak, or periodic with a Moebius map clustering at phi = pi), estimate from the nested levels plus the inner and cut-off bounds";

/// The cloth albedo at view cosine `mu_v` ∈ (0, 1] and Charlie α, to absolute tolerance
/// `tol` (estimated, see the module docs); `Err(evaluations spent)` where the rules do not
/// reach it. A pure function of its arguments.
pub fn charlie_sheen_l(mu_v: f64, alpha: f64, tol: f64) -> Result<Estimate<1>, u64> {
    if !(mu_v > 0.0 && mu_v <= 1.0 && alpha > 0.0 && alpha < MAX_ALPHA && tol > 0.0) {
        return Err(0);
    }
    let k = 0.5 / alpha;
    let norm = (2.0 + 1.0 / alpha) / (2.0 * PI);
    let sv = ((1.0 - mu_v) * (1.0 + mu_v)).max(0.0).sqrt();
    let theta_v = mu_v.acos();
    // μ_cut: s0(μl)^k ≤ eps_t/(norm·π/2) for μl ≥ μ_cut
    let eps_t = 1e-3 * tol;
    let lam = (eps_t / (0.5 * PI * norm)).ln() / k;
    let (mut mu_cut, mut tail) = (1.0, 0.0);
    if lam < 0.0 {
        let th_cut = 2.0 * (0.5 * lam).exp().asin() - theta_v;
        if th_cut >= 0.5 * PI {
            // the whole integrand is below the bound
            return Ok(Estimate {
                value: [0.0],
                error: [eps_t],
                evals: 0,
            });
        }
        if th_cut > 0.0 {
            mu_cut = th_cut.cos();
            tail = eps_t;
        }
    }
    let kappa = mu_v / (1.0 + sv);
    let width = 1.0 / (k * kappa + (k / (2.0 * (1.0 + sv))).sqrt());
    let a = mu_v.min(width).min(mu_cut);
    let big_z = (mu_cut / a).asinh();

    let r = cc_rules();
    let mut done = [false; NMAX];
    let mut val = [0.0; NMAX];
    let mut err = [0.0; NMAX];
    let mut evals = 0u64;
    let inner = Inner {
        mu_v,
        sv,
        k,
        norm,
        budget: 0.05 * tol,
    };
    let mut q = [0.0; MAX_LEVEL + 1];
    for lev in 1..=MAX_LEVEL {
        let stride = 1usize << (MAX_LEVEL - lev);
        let (mut s, mut se) = (0.0, 0.0);
        for (jj, &w) in r.w[lev].iter().enumerate() {
            let i = jj * stride;
            if !done[i] {
                let z = 0.5 * big_z * (1.0 + r.x[i]);
                let ml = a * z.sinh();
                let dml = a * z.cosh() * 0.5 * big_z;
                let (v, e) = inner.node(ml, dml, &mut evals)?;
                val[i] = v;
                err[i] = e;
                done[i] = true;
                if evals > EVAL_CAP {
                    return Err(evals);
                }
            }
            s += w * val[i];
            se += w * err[i];
        }
        q[lev] = s;
        if lev >= 3 {
            let e_out = super::tensor::nested_error(q[lev], q[lev - 1], q[lev - 2], tol);
            let e = e_out + se + tail;
            if !e.is_finite() || !s.is_finite() {
                return Err(evals);
            }
            if e <= tol {
                return Ok(Estimate {
                    value: [s],
                    error: [e],
                    evals,
                });
            }
        }
    }
    Err(evals)
}

/// See [`half_angle_table`].
struct HalfAngle {
    cos2: [f64; M_MAX + 1],
    sin2: [f64; M_MAX + 1],
}

/// cos²(t/2) and sin²(t/2) at the inner grid's t = πj/M_MAX, j = 0..=M_MAX (the Möbius
/// map's nodes, the same for every texel).
fn half_angle_table() -> &'static HalfAngle {
    static H: OnceLock<HalfAngle> = OnceLock::new();
    H.get_or_init(|| {
        let mut h = HalfAngle {
            cos2: [0.0; M_MAX + 1],
            sin2: [0.0; M_MAX + 1],
        };
        for j in 0..=M_MAX {
            let (s, c) = (0.5 * PI * j as f64 / M_MAX as f64).sin_cos();
            h.cos2[j] = c * c;
            h.sin2[j] = s * s;
        }
        h
    })
}

/// One outer node's inner integrand, evaluated a batch at a time.
struct Batch {
    cut: bool,
    half_phi_c: f64,
    phi_c: f64,
    rho2: f64,
    pi_rho: f64,
    big_p: f64,
    big_a: f64,
    big_b: f64,
    s0: f64,
    k: f64,
}

impl Batch {
    /// `out[q]` = (sin²θh/s0)^k · dφ/du at grid index `idx[q]` (u = idx/M_MAX):
    /// straight-line arithmetic so that the loops vectorize.
    #[inline(always)]
    fn eval(&self, idx: &[usize], out: &mut [f64]) {
        let mut xs = [0.0; CHUNK];
        let mut jac = [0.0; CHUNK];
        let n = idx.len();
        if self.cut {
            let du = self.half_phi_c / M_MAX as f64;
            for q in 0..n {
                let (s, _) = sin_cos_poly(du * idx[q] as f64);
                xs[q] = s * s;
                jac[q] = self.phi_c;
            }
        } else {
            let h = half_angle_table();
            for q in 0..n {
                let (cc, ss) = (h.cos2[idx[q]], h.sin2[idx[q]]);
                let den = cc + self.rho2 * ss;
                xs[q] = cc / den;
                jac[q] = self.pi_rho / den;
            }
        }
        for q in 0..n {
            let x = xs[q];
            // sin²θh/s0 = (P − Bx)/(s0 (A − Bx)) ≤ 1
            let ratio = (self.big_p - self.big_b * x) / (self.s0 * (self.big_a - self.big_b * x));
            let keep = if ratio > 1e-300 { 1.0 } else { 0.0 };
            let l = ln_poly(ratio.max(1e-300));
            out[q] = keep * exp_poly((self.k * l).max(-700.0)) * jac[q];
        }
    }
}

/// The inner (φ) rule's per-texel constants.
struct Inner {
    mu_v: f64,
    sv: f64,
    k: f64,
    norm: f64,
    /// error allowed per outer node (times its outer weight, which sum to 2)
    budget: f64,
}

impl Inner {
    /// The outer integrand at μl = `ml` times `dml` (= dμl/dx of the outer rule), and its
    /// error bound; `Err` if the inner rule does not converge within [`M_MAX`].
    fn node(&self, ml: f64, dml: f64, evals: &mut u64) -> Result<(f64, f64), u64> {
        let (mu_v, k) = (self.mu_v, self.k);
        if ml <= 0.0 {
            return Ok((0.0, 0.0));
        }
        let ml = ml.min(1.0);
        let sl = ((1.0 - ml) * (1.0 + ml)).max(0.0).sqrt();
        let b = self.sv * sl;
        let c = mu_v + ml;
        let big_a = 2.0 + 2.0 * (mu_v * ml + b);
        let big_b = 4.0 * b;
        let big_p = big_a - c * c;
        let s0 = big_p / big_a;
        // outer factor: norm · μl V · s0^k · dμl/dx
        let ln_s0 = if s0 > 0.0 { s0.ln() } else { f64::NEG_INFINITY };
        let g = self.norm * ml / (4.0 * (ml + mu_v - ml * mu_v)) * (k * ln_s0).exp() * dml;
        // J ≤ 2π: a node whose bound is far below the budget counts as 0, its bound as error
        if g.is_nan() {
            return Err(*evals);
        }
        if g * 2.0 * PI <= 1e-3 * self.budget {
            return Ok((0.0, g * 2.0 * PI));
        }
        let gamma = k * big_b * c * c / (big_p * big_a);
        // the rule's variable u ∈ [0, 1] → (x = sin²(φ/2), dφ/du)
        let cut = gamma > T_CUT;
        let (phi_c, rho, cut_tail) = if cut {
            let pc = 2.0 * (T_CUT / gamma).sqrt().asin();
            (pc, 1.0, 2.0 * (PI - pc) * (-T_CUT).exp())
        } else {
            (PI, (0.5 * k.sqrt() * c).min(1.0), 0.0)
        };
        let bat = Batch {
            cut,
            half_phi_c: 0.5 * phi_c,
            phi_c,
            rho2: rho * rho,
            pi_rho: PI * rho,
            big_p,
            big_a,
            big_b,
            s0,
            k,
        };
        // trapezoid on [0, 1] in u (grid index j ↔ u = j/M_MAX), doubled for [−1, 0]
        // (even integrand); new nodes of each level in fixed-size batches, summed in order
        let mut idx = [0usize; CHUNK];
        let mut out = [0.0; CHUNK];
        let mut m = 8usize;
        let n0 = m + 1;
        for j in 0..n0 {
            idx[j] = j * (M_MAX / m);
        }
        bat.eval(&idx[..n0], &mut out[..n0]);
        let mut sum = 0.5 * (out[0] + out[m]);
        for j in 1..m {
            sum += out[j];
        }
        *evals += n0 as u64;
        let mut t_prev = 2.0 * sum / m as f64;
        while m < M_MAX {
            let step = M_MAX / (2 * m);
            let mut j0 = 0;
            while j0 < m {
                let c = CHUNK.min(m - j0);
                for j in 0..c {
                    idx[j] = (2 * (j0 + j) + 1) * step;
                }
                bat.eval(&idx[..c], &mut out[..c]);
                for j in 0..c {
                    sum += out[j];
                }
                j0 += c;
            }
            *evals += m as u64;
            m *= 2;
            let t = 2.0 * sum / m as f64;
            let e = (t - t_prev).abs();
            if e * g <= self.budget || e <= 1e-14 * t {
                return Ok((g * t, g * (e + cut_tail) + 1e-15 * g * t));
            }
            t_prev = t;
        }
        Err(*evals)
    }
}

/// The cloth albedo at normal view (μv = 1), where h bisects n and l, sin²θh = (1 − μl)/2
/// and `(π/2)·norm·∫₀¹ μl ((1 − μl)/2)^k dμl = (π/2)·norm·2^{−k}/((k + 1)(k + 2))` (a Beta
/// integral, B(2, k + 1)): the closed form the light-coordinate paths are tested against.
#[cfg(test)]
pub(crate) fn normal_view_albedo(alpha: f64) -> f64 {
    let k = 0.5 / alpha;
    let norm = (2.0 + 1.0 / alpha) / (2.0 * PI);
    0.5 * PI * norm * (-k * std::f64::consts::LN_2).exp() / ((k + 1.0) * (k + 2.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At normal view the albedo has a closed form ([`normal_view_albedo`]). The path must
    /// agree within its own estimate plus rounding (1e-13 relative: a few hundred terms of the
    /// value's size), and its estimate must meet the tolerance.
    #[test]
    fn normal_view_matches_closed_form() {
        for &alpha in &[0.06, 0.03, 0.01, 3e-3, 1e-3, 1e-4, 1e-6] {
            let exact = normal_view_albedo(alpha);
            for tol in [1e-7, 1e-10] {
                let e = charlie_sheen_l(1.0, alpha, tol).expect("converges at normal view");
                let d = (e.value[0] - exact).abs();
                assert!(
                    e.error[0] <= tol && d <= e.error[0] + 1e-13 * exact,
                    "alpha={alpha} tol={tol}: {e:?} vs {exact}"
                );
            }
        }
    }
}
