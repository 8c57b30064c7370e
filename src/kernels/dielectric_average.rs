//! The average albedo of a rough dielectric interface, E_avg = 2∫₀¹ E(μ) μ dμ with
//! E = R + T (`dielectric-albedo-avg`: Cycles' `glass_Eavg`, `glass_inv_Eavg`), as one
//! three-dimensional integral in micro-normal coordinates instead of a μ-integral of
//! directional albedos (each itself two-dimensional).
//!
//! **Reduction.** With R(μ) = ∫ D(h) G(v, l_r) F(c) c/μ dω_h and T(μ) likewise (c = v·h,
//! `crate::model::btdf`), 2∫ μ E dμ = (1/π) ∫_{v} μ E(v) dω_v, and exchanging the order:
//!
//! `E_avg = (1/π) ∫ D(h) Φ(θh) dω_h`, `Φ(θh) = ∫_{v·h > 0, n·v > 0} c [F(c) G(v, l_r) +
//! (1 − F(c)) G(v, l_t)] dω_v`
//!
//! (each term only where its direction leaves on its own side). Isotropy makes Φ a function
//! of θh alone, so the NDF's peak is one-dimensional: the outer integral runs over
//! u = asinh(tan θh/α), where `D sin θh dθh = sinh u √(1 + α² sinh²u)/(π cosh³u) du`, and
//! the NDF leaves the inner integrals. In coordinates of v about h — c = v·h and the azimuth
//! ψ about h, measured from the plane of n and h (dω_v = dc dψ, n = cos θh h + sin θh e₁) —
//! with a = c cos θh, b = √(1 − c²) sin θh: n·v = a + b cos ψ, n·l_r = a − b cos ψ
//! (l_r = 2c h − v), and n·l_t = (c/η − cos θt) cos θh − (n·v)/η with cos θt =
//! √(1 − (1 − c²)/η²) (Walter et al. 2007, eq. 40). So
//!
//! `Φ = 2∫₀¹ c [F(c) J_r(c) + (1 − F(c)) J_t(c)] dc`, `J_r = 2∫_{ψ_r}^{π/2} G dψ`,
//! `J_t = ∫₀^{ψ_t} G dψ`,
//!
//! with the ranges in closed form: n·v > 0 and n·l_r > 0 for |cos ψ| < a/b (ψ_r = acos(a/b),
//! 0 if a ≥ b; the integrand is symmetric about ψ = π/2), n·v > 0 and n·l_t < 0 for
//! cos ψ > −m/b with m = min(c, η cos θt) cos θh (ψ_t = acos(−m/b), π if m ≥ b); no
//! transmission under total internal reflection (1 − c² ≥ η²). Fresnel's F(c) has its
//! square-root kink at the critical cosine √(1 − η²), a coordinate line here; the other
//! kinks of the c-integrand are where the ψ-ranges become whole: c = sin θh (a = b) and,
//! for η < 1, c = √(1 − η² cos²θh) (η cos θt cos θh = b). All three are panel boundaries,
//! treated as square-root ends (the panels beside them in t, c = end ± (b − a) t²); in u,
//! θh = acos η (η < 1), where c = sin θh meets the critical cosine, is one too. (The
//! panel ends where G's layers are, `layer` and c = α·4^k, are plain ends: G is smooth
//! there.) Each integral is nested Clenshaw–Curtis per panel, adaptive Gauss–Kronrod where
//! that fails ([`crate::quadrature::cc1d::cc_or_adaptive`]), with the tail estimate in c and
//! ψ and the standard one in u.
//!
//! **Sharing.** J_r does not depend on η; the η ≥ 1 slices have the same ψ-ranges and
//! c-breakpoints, so up to N of them are the channels of one rule, sharing every node and
//! J_r. (An η < 1 slice goes alone: its breakpoints are its own.)
//!
//! **Error.** Outer rule: half the tolerance. The outer integrand's weight integrates to
//! `(1/π)∫D dω_h ≤ 1/π + α/2` (∫D dω_h = 2α²∫ x√(1 + x²)/(α² + x²)² dx ≤ 1 + πα/2 with
//! √(1 + x²) ≤ 1 + x, x = tan θh), so Φ is wanted to `tol/4/(1/π + α/2)`: half for its
//! c-rule, half for the J's (2∫₀¹ c dc = 1 carries a J error into Φ unchanged). The reported
//! estimate is the outer rule's plus that weight times the largest Φ estimate. The u-range
//! ends where the weight's tail, ≤ 8α e^(−U) + 8 e^(−2U) times Φ ≤ π (∫ c dω_v = π), is
//! below 1e-3 of the tolerance.

use super::micro_normals::{panels, Breaks};
use crate::model::btdf::SmithForm;
use crate::model::fresnel::dielectric;
use crate::model::{Ndf, NdfKind};
use crate::numerics::cos_0_pi;
use crate::quadrature::cc1d::Estimator;
use crate::quadrature::{Estimate, Tolerance};
use std::f64::consts::{FRAC_PI_2, PI};

/// Finest nested Clenshaw–Curtis level per panel: 65 nodes in each variable.
const OUTER_LEVEL: usize = 6;
const MIDDLE_LEVEL: usize = 6;
const INNER_LEVEL: usize = 6;

/// Below this α the middle rule gets no panel ends where c ~ α·4^k (both directions
/// graze at small θh): there G's layers hold less than ~α ≤ 1e-6 of Φ, and at α = 1e-8
/// (Cycles' clamped roughness) those 13 extra panels, each with its ψ integrals, took 4× the
/// nodes of the whole texel for nothing (the η ≥ 1 texels of `cycles-glass-eavg`).
const MIDDLE_LAYER_ALPHA: f64 = 1e-6;

/// Most layer breaks per range ([`layer`]): layers finer than 4⁻¹⁶ of the range's largest
/// distance (below 1e-9 of it) get none.
const MAX_LAYERS: u32 = 16;

/// Panel ends in ψ where the distance `d` of a direction to its horizon is α·4^k, k = 0, 1,
/// …, for d between `d_min` (its smallest on the range, 0 where the range ends at the
/// horizon) and half of `span` (its largest); `psi_of(d)` gives ψ. The masking
/// G1(d) = 2d/(d + √(α² + (1 − α²)d²)) varies on the scale α there, far below the panel's
/// length for narrow lobes, and a range that only comes near the horizon (d_min > 0 but
/// small: where n·l_r touches 0, c ≈ sin θh) has the same layer. Without these ends the
/// nested rule failed and the adaptive one took ~16,000 nodes per range at α = 1e-8
/// (Cycles' clamped roughness), 85M of the 93M nodes of its costliest texel.
fn layer(
    br: &mut Breaks,
    alpha: f64,
    d_min: f64,
    span: f64,
    psi_of: impl Fn(f64) -> f64,
    lo: f64,
    hi: f64,
) {
    // (a range that stays 4α or more from the horizon sees G1 only as 1 − O(α²/d²): smooth)
    if d_min >= 4.0 * alpha {
        return;
    }
    let mut d = alpha.max(0.5 * span * 0.25f64.powi(MAX_LAYERS as i32));
    while d < 0.5 * span {
        if d > d_min {
            let p = psi_of(d);
            if p > lo && p < hi {
                br.push(p, false);
            }
        }
        d *= 4.0;
    }
}

/// A tolerance for [`panels`] whose integrand is known to ±`noise` per unit length.
fn tolerance(abs: f64, noise: f64) -> Tolerance {
    Tolerance {
        abs,
        initial_panels: 2,
        max_depth: 40,
        noise_floor: 4.0 * noise,
        max_evals: 100_000,
    }
}

/// E_avg of each relative index in `etas` (all ≥ 1, up to N; or a single one below 1) for
/// the GGX NDF `ndf` with masking `smith`, to absolute tolerance `tol` each: channel k is
/// `etas[k]`'s (channels beyond `etas.len()` are 0). `evals` counts the ψ nodes.
pub fn average_albedo<const N: usize>(
    ndf: &Ndf,
    smith: SmithForm,
    etas: &[f64],
    tol: f64,
) -> Estimate<N> {
    debug_assert!(etas.len() <= N);
    assert!(
        ndf.kind() == NdfKind::Ggx,
        "GGX only (the masking is GGX's)"
    );
    debug_assert!(etas.len() == 1 || etas.iter().all(|&e| e >= 1.0));
    let alpha = ndf.alpha();
    let a2 = alpha * alpha;
    let below = etas.iter().copied().find(|&e| e < 1.0);
    // ∫₀¹ (2/π) √(s² + α²(1 − s²)) ds ≤ (2/π) max(1, α)
    let weight_total = 2.0 / PI * alpha.max(1.0);
    let phi_tol = 0.25 * tol / weight_total;
    let j_tol = 0.5 * phi_tol;
    let evals = std::cell::Cell::new(0u64);
    let phi_err = std::cell::Cell::new([0.0f64; N]);
    let j_err = std::cell::Cell::new(0.0f64);
    // per unit length of the outer variable: the outer integrand's noise from Φ's
    let outer_noise = weight_total * phi_tol;
    // Φ(θh) per index
    let phi_of = |cos_h: f64, sin_h: f64| -> [f64; N] {
        // the inner integrands at one c: the range ends and G per direction
        let g = |nv: f64, nl: f64| smith.ggx(a2, nv, nl);
        let middle = |c: f64| -> [f64; N] {
            let mut out = [0.0; N];
            let s2 = (1.0 - c) * (1.0 + c);
            let s = s2.max(0.0).sqrt();
            let (a, b) = (c * cos_h, s * sin_h);
            // J_r: 2∫ over [ψ_r, π/2] (symmetric about π/2)
            let psi_r = if a >= b { 0.0 } else { (a / b).acos() };
            let jr = {
                let mut br = Breaks::new();
                br.push(psi_r, false);
                br.push(FRAC_PI_2, false);
                // G1 drops to 0 over n.l ~ alpha at the horizon (psi_r, where
                // n.l_r = a - b cos psi = 0), or near it where n.l_r's least value a - b
                // (at psi = 0) is small: panel ends at n.l_r = alpha 4^k
                if b > 0.0 {
                    layer(
                        &mut br,
                        alpha,
                        (a - b).max(0.0),
                        a,
                        |d| ((a - d) / b).clamp(-1.0, 1.0).acos(),
                        psi_r,
                        FRAC_PI_2,
                    );
                }
                let e = panels(
                    |psi: f64| {
                        let bc = b * cos_0_pi(psi);
                        [g(a + bc, a - bc)]
                    },
                    br,
                    tolerance(0.5 * j_tol, 0.0),
                    INNER_LEVEL,
                    Estimator::Tail,
                );
                evals.set(evals.get() + e.evals);
                j_err.set(j_err.get().max(2.0 * e.error[0]));
                2.0 * e.value[0]
            };
            // J_t per index: the same range for every η ≥ 1 (m = a there)
            let mut jt = [0.0; N];
            let mut refr = [None; N];
            for (o, &eta) in refr.iter_mut().zip(etas) {
                let r = s2 / (eta * eta);
                *o = (r < 1.0).then(|| (1.0 - r).sqrt());
            }
            if refr.iter().any(Option::is_some) {
                let m = match (below, refr.first().copied().flatten()) {
                    (Some(eta), Some(ct)) => c.min(eta * ct) * cos_h,
                    _ => a,
                };
                let psi_t = if m >= b { PI } else { (-m / b).acos() };
                let mut br = Breaks::new();
                br.push(0.0, false);
                br.push(psi_t, false);
                // the horizon at psi_t, where n.v = a + b cos psi falls to
                // m' = max(0, (c - eta cos theta_t) cos theta_h) (n.v = 0 binds for eta >= 1,
                // n.l_t = 0 for eta < 1 where m' > 0): its layer, in units of n.v
                // (or near it, where the least distance m - b at psi = pi is small); where
                // n.l_t = 0 binds, n.l_t = (n.v - m')/eta, so G1(n.l_t)'s layer is eta alpha
                // wide in n.v
                if b > 0.0 {
                    let lo = a - m;
                    let scale = match below {
                        Some(eta) if m < a => alpha * eta,
                        _ => alpha,
                    };
                    layer(
                        &mut br,
                        scale,
                        (m - b).max(0.0),
                        a + b - lo,
                        |d| ((lo + d - a) / b).clamp(-1.0, 1.0).acos(),
                        0.0,
                        psi_t,
                    );
                }
                let e = panels(
                    |psi: f64| {
                        let nv = a + b * cos_0_pi(psi);
                        let mut y = [0.0; N];
                        for (k, (&eta, ct)) in etas.iter().zip(&refr).enumerate() {
                            if let Some(ct) = ct {
                                let nlt = (c / eta - ct) * cos_h - nv / eta;
                                if nlt < 0.0 {
                                    y[k] = g(nv, -nlt);
                                }
                            }
                        }
                        y
                    },
                    br,
                    tolerance(j_tol, 0.0),
                    INNER_LEVEL,
                    Estimator::Tail,
                );
                evals.set(evals.get() + e.evals);
                j_err.set(
                    j_err
                        .get()
                        .max(e.error.iter().fold(0.0, |m: f64, &x| m.max(x))),
                );
                jt = e.value;
            }
            for (k, &eta) in etas.iter().enumerate() {
                let f = dielectric(c, eta);
                out[k] = 2.0 * c * (f * jr + (1.0 - f) * jt[k]);
            }
            out
        };
        let mut br = Breaks::new();
        br.push(0.0, false);
        br.push(1.0, false);
        let mut inside = |x: f64, singular: bool| {
            if x > 0.0 && x < 1.0 {
                br.push(x, singular);
            }
        };
        inside(sin_h, true);
        // where c ~ alpha both directions graze (theta_h small): G's layer in c (smooth
        // panel ends, not kinks)
        let mut k = alpha;
        while k < 0.5 && k > MIDDLE_LAYER_ALPHA {
            inside(k, false);
            k *= 4.0;
        }
        if let Some(eta) = below {
            inside(((1.0 - eta) * (1.0 + eta)).sqrt(), true);
            inside((1.0 - eta * eta * cos_h * cos_h).max(0.0).sqrt(), true);
        }
        let e = panels(
            middle,
            br,
            tolerance(0.5 * phi_tol, j_tol),
            MIDDLE_LEVEL,
            Estimator::Tail,
        );
        let mut pe = phi_err.get();
        for (m, &x) in pe.iter_mut().zip(&e.error) {
            *m = m.max(x);
        }
        phi_err.set(pe);
        e.value
    };
    let outer = |s: f64| -> [f64; N] {
        // tan θh = α √(1 − s²)/s; w = √(s² + α²(1 − s²)) = s/cos θh
        let c2 = (1.0 - s) * (1.0 + s);
        let w = (s * s + alpha * alpha * c2).sqrt();
        let (cos_h, sin_h) = if w > 0.0 {
            (s / w, alpha * c2.sqrt() / w)
        } else {
            (0.0, 1.0)
        };
        let mut y = phi_of(cos_h, sin_h);
        for v in y.iter_mut() {
            *v *= 2.0 / PI * w;
        }
        y
    };
    let mut br = Breaks::new();
    br.push(0.0, false);
    br.push(1.0, false);
    // for narrow lobes the weight turns from α to s around s ~ α (θh ~ 45°): panel ends at
    // α 4^k
    let mut x = alpha;
    while x < 0.5 {
        br.push(x, false);
        x *= 4.0;
    }
    if let Some(eta) = below {
        // θh = acos η: tan θh = √(1 − η²)/η; where the middle rule's square-root ends
        // sin θh and √(1 − η²) cross, a square-root end here too (as a plain end the panel
        // beside it missed its estimate: at η = 0.99115, α = 1 an error of 5.8e-8 against
        // 1.6e-8, examples/eavg_probe.rs)
        let x = alpha * eta / ((1.0 - eta) * (1.0 + eta) + alpha * alpha * eta * eta).sqrt();
        if x > 0.0 && x < 1.0 {
            br.push(x, true);
        }
    }
    let e = panels(
        outer,
        br,
        tolerance(0.5 * tol, outer_noise),
        OUTER_LEVEL,
        // (the standard estimate: with the tail one the estimate fell below the error at 10
        // of the 256 texels of Cycles' glass_Eavg grid and 2 of glass_inv_Eavg's, by up to
        // 2×; with this one at none, examples/eavg_probe.rs at 1e-7 against 1e-10)
        Estimator::Standard,
    );
    let pe = phi_err.get();
    let je = j_err.get();
    Estimate {
        value: e.value,
        error: std::array::from_fn(|k| e.error[k] + weight_total * (pe[k] + je)),
        evals: evals.get(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The estimates hold at the texels of Cycles' grids where they did not with the tail
    /// estimate in u (or with θh = acos η as a plain panel end): each value at 1e-7 within
    /// its own estimate of the same rule at 1e-10 (plus that one's estimate). Cycles' axes:
    /// α = (j/15)², x = (k/15)², η = (1 − x)/(1 + x) for glass_inv_Eavg (each texel
    /// alone), η = (1 + x)/(1 − x) for glass_Eavg (k = 8..15 as one rule of 8, as the bake
    /// groups them); before, errors of 5.8e-8 against 1.6e-8 (j = 15, k = 1) and 3.5e-8
    /// against 1.8e-8 (j = 13, η = 2.6) (examples/eavg_probe.rs).
    #[test]
    fn estimates_hold_where_the_tail_estimate_did_not() {
        let smith = SmithForm::HeightCorrelated;
        let x = |k: usize| (k as f64 / 15.0).powi(2);
        let ggx = |j: usize| Ndf::new(NdfKind::Ggx, x(j)).unwrap();
        let check = |ndf: &Ndf, etas: &[f64]| {
            let e = average_albedo::<8>(ndf, smith, etas, 1e-7);
            for (c, &eta) in etas.iter().enumerate() {
                let r = average_albedo::<1>(ndf, smith, &[eta], 1e-10);
                let d = (e.value[c] - r.value[0]).abs();
                assert!(
                    d <= e.error[c] + r.error[0],
                    "alpha {} eta {eta}: error {d:e} over its estimate {:e}",
                    ndf.alpha(),
                    e.error[c]
                );
            }
        };
        for (j, k) in [(15, 1), (14, 1), (11, 10)] {
            check(&ggx(j), &[(1.0 - x(k)) / (1.0 + x(k))]);
        }
        // (x clamped to 0.9801 as Cycles' axis is)
        let glass: Vec<f64> = (8..16)
            .map(|k| (1.0 + x(k).min(0.9801)) / (1.0 - x(k).min(0.9801)))
            .collect();
        check(&ggx(13), &glass);
    }

    /// Cycles' clamped roughness (α = 1e-8) at its tolerance 1e-7: E_avg within the tolerance
    /// of the smooth limit 1 (a smooth interface reflects or transmits everything; masking
    /// costs O(α)), each estimate within the tolerance, and the nested rules' layer breaks
    /// keep the work bounded: at η = 0.01005, without them the adaptive fallback took 93M
    /// nodes (with them ~2M), so 5M is a bound that fails without them.
    #[test]
    fn clamped_roughness_is_cheap_and_at_its_smooth_limit() {
        let ndf = Ndf::new(NdfKind::Ggx, 1e-8).unwrap();
        let tol = 1e-7;
        for eta in [0.01005, 0.06888, 0.8, 1.5] {
            for smith in [SmithForm::HeightCorrelated, SmithForm::Separable] {
                let e = average_albedo::<1>(&ndf, smith, &[eta], tol);
                assert!(e.error[0] <= tol, "eta {eta} {smith:?}: {e:?}");
                assert!(
                    (e.value[0] - 1.0).abs() <= tol,
                    "eta {eta} {smith:?}: {e:?}"
                );
                assert!(
                    e.evals < 5_000_000,
                    "eta {eta} {smith:?}: {} nodes",
                    e.evals
                );
            }
        }
    }
}
