//! Integrals over the outgoing hemisphere, parameterized by the half vector.
//!
//! Every reflectance integral brdfbake bakes has the form
//! `I(v) = ∫_{n·l>0} g(v, l) dω_l`. Microfacet BRDFs concentrate around `h = n`, so we
//! integrate over the half vector `h = (θh, φ)` with `dω_l = 4 (v·h) dω_h` (Walter et al.
//! 2007, eq. 14) and let `v` lie in the xz-plane (isotropy), so `φ ∈ [0, π]` counts twice.
//!
//! **Horizon, solved exactly.** With `tan ψ = tan θv cos φ`, one finds
//! `n·l = 2(v·h)(n·h) − n·v = A cos(2θh − ψ)`, `A = √(cos²θv + sin²θv cos²φ)`, so the
//! reflected direction is above the horizon iff `θh < θmax(φ) = π/4 + ψ/2`; below that
//! limit `v·h > 0` automatically. Integrating exactly up to `θmax` keeps the integrand
//! smooth (it vanishes linearly at the limit) instead of cutting it with a step.
//!
//! **Lobe warp.** For NDFs peaked at `h = n` the inner variable is `u = asinh(tan θh / α)`:
//! in `u` the GGX measure `D cos θh dω_h` becomes `2 sinh u / cosh³ u du`, which decays
//! exponentially, so the quadrature sees an O(1)-wide smooth bump whatever α is. Sheen
//! (Charlie) NDFs peak at grazing half vectors instead and use θh itself.
//!
//! **Grazing views.** As θv → 90°, ψ swings from +θv to −θv in a φ-interval of width
//! ~cos θv around φ = π/2, so the φ range is split there and refined adaptively.

pub mod monte_carlo;
pub mod tensor;

use crate::quadrature::adaptive::{integrate, Estimate, Tolerance};
use std::f64::consts::{FRAC_PI_2, PI};

/// Everything an integrand may need at one node, all cosines with respect to the normal.
#[derive(Clone, Copy, Debug)]
pub struct Node {
    pub n_dot_v: f64,
    pub n_dot_l: f64,
    pub n_dot_h: f64,
    /// `v·h = l·h`.
    pub v_dot_h: f64,
    /// sin²θh, computed directly rather than as 1 − (n·h)²: for narrow lobes (α ~ 1e-5)
    /// 1 − cos² loses all but a few digits, and D needs it.
    pub sin2_h: f64,
}

impl Node {
    /// The node for a view `v = (sin θv, 0, cos θv)` (`mu_v = cos θv`, `sin_v = sin θv`) and a
    /// half vector at polar angle θh and azimuth φ (`cos_phi = cos φ`): `v·h` from the two
    /// polar angles, `n·l = 2(v·h)(n·h) − n·v` from `l = 2(v·h)h − v`.
    #[inline]
    pub fn at(mu_v: f64, sin_v: f64, cos_phi: f64, sin_h: f64, cos_h: f64) -> Node {
        let v_dot_h = sin_v * sin_h * cos_phi + mu_v * cos_h;
        Node {
            n_dot_v: mu_v,
            n_dot_l: 2.0 * v_dot_h * cos_h - mu_v,
            n_dot_h: cos_h,
            v_dot_h,
            sin2_h: sin_h * sin_h,
        }
    }
}

/// How the inner (θh) variable is warped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LobeWarp {
    /// `u = asinh(tan θh / scale)`: for lobes of width `scale` around the normal.
    TanOverScale(f64),
    /// θh itself: for lobes that are not concentrated at the normal (wide sheen).
    Linear,
    /// `θh = θmax − w·sinh u` with `w = min(α·tan θmax, √α)`: for a narrow sheen lobe
    /// `sin^{1/α} θh` (Charlie, α ≪ 1), which peaks at θh = π/2, beyond the horizon limit
    /// θmax(φ) < π/2, so that what the integral sees is its flank pressed against the limit:
    /// `ln sin θh ≈ ln sin θmax − x·cot θmax − x²/(2 sin²θmax)` with `x = θmax − θh`, i.e. a
    /// decay over `x ~ α·tan θmax` (or `√α` where cot θmax → 0). Linear θh nodes miss a
    /// spike that narrow (α = 1e-9 took minutes); in u it is O(1) wide.
    SheenFlank(f64),
    /// As `TanOverScale`, with the θh range also split where Cook–Torrance's V-groove term
    /// `G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h))` switches branch (see
    /// [`vgroove_kinks`]): a kink inside a Gauss–Kronrod panel makes K15 and G7 agree on a
    /// wrong value (false convergence), a kink at a panel edge costs nothing.
    TanOverScaleVGroove(f64),
}

/// The half-vector polar angles θh in `(0, θmax)` at which the V-groove term can switch
/// branch, for a view with `tan ψ = tan θv cos φ` (`psi` in (−π/2, π/2)), sorted.
///
/// With `v = (sin θv, 0, cos θv)` and `h` at (θh, φ), `v·h = cos θh cos θv (1 + tan θh tan ψ)`.
/// * `2(n·h)(n·v) = v·h` ⇔ `tan θh tan ψ = 1` ⇔ `θh = π/2 − ψ` (ψ > 0).
/// * `2(n·h)(n·l) = v·h` with `n·l = 2(v·h)(n·h) − n·v` ⇔, dividing by cos³θh cos θv and
///   writing `t = tan θh`, `s = tan ψ`: `s(t³ − 3t) + (3t² − 1) = 0` ⇔
///   `tan 3θh = (3t − t³)/(1 − 3t²) = −1/s` ⇔ `θh = (ψ + π/2)/3` (the only root in
///   [0, θmax] — the others are negative or beyond the horizon).
/// * the two branches cross where `n·l = n·v` ⇔ `cos²θh (1 + tan θh tan ψ) = 1` ⇔
///   `θh = ψ` (ψ > 0).
///
/// Derived here; the V-groove term itself is Cook & Torrance (1982), eq. 6 (after
/// Torrance & Sparrow 1967).
pub fn vgroove_kinks(psi: f64) -> Vec<f64> {
    let th_max = std::f64::consts::FRAC_PI_4 + 0.5 * psi;
    let mut k: Vec<f64> = [(psi + FRAC_PI_2) / 3.0, FRAC_PI_2 - psi, psi]
        .into_iter()
        .filter(|&t| t > 0.0 && t < th_max)
        .collect();
    k.sort_by(f64::total_cmp);
    k
}

/// Most integrand evaluations one hemisphere integral may spend (≈ 2 s at ~100 ns each):
/// once the inner integrals have used this many, each further one gets only its initial
/// panels, so the nested rule's cost is bounded (≈ 2.2·10⁷ evaluations, the outer rule's
/// own budget included) even for an integrand that never reaches the tolerance; the error
/// estimates it then reports say so. Default-tolerance tables use 10³–10⁵ per texel.
pub const TEXEL_EVAL_BUDGET: u64 = 20_000_000;

/// `tan θmax(φ)` for a view with `tan θv = tan_v`, computed without cancellation.
#[inline]
pub fn tan_theta_h_max(tan_v: f64, cos_phi: f64) -> f64 {
    let t = tan_v * cos_phi; // tan ψ
    let s = (1.0 + t * t).sqrt(); // sec ψ
    if t >= 0.0 {
        s + t
    } else {
        1.0 / (s - t)
    }
}

/// The tolerances of a nested φ/θh quadrature over the hemisphere to absolute tolerance
/// `tol_abs`: (inner, outer), the outer one for the whole φ range [0, π] (doubled by mirror
/// symmetry). Budget: half to the outer φ integral, half to the inner integrals (their errors
/// add up over a φ-range of π, doubled). The inner integrals are the outer integrand, so
/// their error is noise to the outer rule: bisecting the outer panels below that noise
/// floor would only chase it, hence `noise_floor`.
pub(crate) fn nested_tolerances(tol_abs: f64) -> (Tolerance, Tolerance) {
    let inner_abs = tol_abs / (4.0 * PI);
    let inner = Tolerance {
        abs: inner_abs,
        initial_panels: 2,
        max_depth: 40,
        max_evals: 100_000,
        ..Default::default()
    };
    let outer = Tolerance {
        abs: tol_abs / 2.0,
        initial_panels: 2,
        max_depth: 40,
        noise_floor: 4.0 * inner_abs,
        max_evals: 30_000,
    };
    (inner, outer)
}

/// [`integrate`] over consecutive pieces `[cuts[i], cuts[i+1]]`, the tolerance shared in
/// proportion to length (as `integrate` shares it among its own panels).
fn integrate_pieces<const N: usize, F: FnMut(f64) -> [f64; N]>(
    mut f: F,
    cuts: &[f64],
    tol: Tolerance,
) -> Estimate<N> {
    let (a, b) = (cuts[0], cuts[cuts.len() - 1]);
    if cuts.len() == 2 {
        return integrate(f, a, b, tol);
    }
    let mut out = Estimate::zero();
    for w in cuts.windows(2) {
        let share = Tolerance {
            abs: tol.abs * (w[1] - w[0]) / (b - a),
            ..tol
        };
        let e = integrate(&mut f, w[0], w[1], share);
        for c in 0..N {
            out.value[c] += e.value[c];
            out.error[c] += e.error[c];
        }
        out.evals += e.evals;
    }
    out
}

/// Integrates `g(v, l) dω_l` over the upper hemisphere of `l` for a view with cosine
/// `n_dot_v ∈ (0, 1]`. `tol_abs` is the target absolute error of the whole integral.
pub fn integrate_over_l<const N: usize, F: Fn(&Node) -> [f64; N]>(
    n_dot_v: f64,
    warp: LobeWarp,
    tol_abs: f64,
    g: F,
) -> Estimate<N> {
    let mu_v = n_dot_v.min(1.0);
    let sin_v = (1.0 - mu_v * mu_v).max(0.0).sqrt();
    let tan_v = sin_v / mu_v;
    let (inner_tol, outer_whole) = nested_tolerances(tol_abs);
    // per half-range, and each is doubled by symmetry
    let outer_tol = Tolerance {
        abs: outer_whole.abs / 2.0,
        ..outer_whole
    };
    let inner_err = std::cell::Cell::new(0.0f64);
    let inner_evals = std::cell::Cell::new(0u64);
    let phi_integrand = |phi: f64| -> [f64; N] {
        let (sp, cp) = phi.sin_cos();
        let tmax = tan_theta_h_max(tan_v, cp);
        let node_at = |sin_h: f64, cos_h: f64| Node::at(mu_v, sin_v, cp, sin_h, cos_h);
        let _ = sp;
        let left = TEXEL_EVAL_BUDGET.saturating_sub(inner_evals.get());
        let inner_tol = Tolerance {
            max_evals: inner_tol.max_evals.min(left.max(30)),
            ..inner_tol
        };
        let est = match warp {
            LobeWarp::TanOverScale(scale) | LobeWarp::TanOverScaleVGroove(scale) => {
                let umax = (tmax / scale).asinh();
                // breakpoints in u: the V-groove kinks, if asked for
                let mut cuts = vec![0.0];
                if let LobeWarp::TanOverScaleVGroove(_) = warp {
                    let psi = (tan_v * cp).atan();
                    for th in vgroove_kinks(psi) {
                        let u = (th.tan() / scale).asinh();
                        if u > 0.0 && u < umax {
                            cuts.push(u);
                        }
                    }
                }
                cuts.push(umax);
                integrate_pieces(
                    |u: f64| {
                        let t = scale * u.sinh();
                        let c2 = 1.0 / (1.0 + t * t);
                        let cos_h = c2.sqrt();
                        let sin_h = t * cos_h;
                        let n = node_at(sin_h, cos_h);
                        if n.n_dot_l <= 0.0 || n.v_dot_h <= 0.0 {
                            return [0.0; N];
                        }
                        // dω_h = sin θh dθh dφ, dθh/du = scale·cosh u · cos²θh; dω_l = 4(v·h)dω_h
                        let jac = 4.0 * n.v_dot_h * sin_h * scale * u.cosh() * c2;
                        let mut y = g(&n);
                        for v in y.iter_mut() {
                            *v *= jac;
                        }
                        y
                    },
                    &cuts,
                    inner_tol,
                )
            }
            LobeWarp::SheenFlank(alpha) => {
                let thmax = tmax.atan();
                let w = (alpha * tmax).min(alpha.sqrt());
                let umax = (thmax / w).asinh();
                integrate(
                    |u: f64| {
                        let x = w * u.sinh();
                        let th = (thmax - x).max(0.0);
                        let (sin_h, cos_h) = th.sin_cos();
                        let n = node_at(sin_h, cos_h);
                        if n.n_dot_l <= 0.0 || n.v_dot_h <= 0.0 {
                            return [0.0; N];
                        }
                        // dθh/du = −w·cosh u (the sign flips the limits back)
                        let jac = 4.0 * n.v_dot_h * sin_h * w * u.cosh();
                        let mut y = g(&n);
                        for v in y.iter_mut() {
                            *v *= jac;
                        }
                        y
                    },
                    0.0,
                    umax,
                    inner_tol,
                )
            }
            LobeWarp::Linear => {
                let thmax = tmax.atan();
                integrate(
                    |th: f64| {
                        let (sin_h, cos_h) = th.sin_cos();
                        let n = node_at(sin_h, cos_h);
                        if n.n_dot_l <= 0.0 || n.v_dot_h <= 0.0 {
                            return [0.0; N];
                        }
                        let jac = 4.0 * n.v_dot_h * sin_h;
                        let mut y = g(&n);
                        for v in y.iter_mut() {
                            *v *= jac;
                        }
                        y
                    },
                    0.0,
                    thmax,
                    inner_tol,
                )
            }
        };
        inner_err.set(inner_err.get().max(est.max_error()));
        inner_evals.set(inner_evals.get() + est.evals);
        est.value
    };
    let mut total = Estimate::<N>::zero();
    // For the V-groove term, the inner integral is not smooth in φ where a kink enters the
    // θh range at the horizon (tan ψ = 1/√3, ψ = π/6) or two kinks meet (tan ψ = 1,
    // ψ = π/4): split [0, π/2] there (tan ψ = tan θv cos φ falls from tan θv to 0).
    let mut first = vec![0.0];
    if let LobeWarp::TanOverScaleVGroove(_) = warp {
        for t in [1.0, 1.0 / 3f64.sqrt()] {
            if tan_v > t {
                first.push((t / tan_v).acos());
            }
        }
    }
    // At grazing views ψ swings from +θv to −θv within |φ − π/2| ~ cot θv (see the module
    // doc): a feature that narrow at the end of an O(1) panel falls between the Kronrod
    // nodes (the node nearest an end of a 15-point panel of width h is ~0.004·h in), so K15
    // and G7 can agree on a wrong value. Cuts graded geometrically towards π/2,
    // φ = π/2 ∓ cot θv·4^k, give the feature panels of its own width.
    let mut second = vec![FRAC_PI_2];
    let cot_v = mu_v / sin_v;
    if cot_v < 0.25 {
        let mut d = cot_v;
        while d < 0.5 {
            first.push(FRAC_PI_2 - d);
            second.push(FRAC_PI_2 + d);
            d *= 4.0;
        }
        first.sort_by(f64::total_cmp);
        second.sort_by(f64::total_cmp);
    }
    first.push(FRAC_PI_2);
    second.push(PI);
    for cuts in [first, second] {
        let e = integrate_pieces(phi_integrand, &cuts, outer_tol);
        for c in 0..N {
            total.value[c] += 2.0 * e.value[c];
            total.error[c] += 2.0 * e.error[c];
        }
    }
    // inner errors integrate over φ ∈ [0, π], doubled
    for c in 0..N {
        total.error[c] += 2.0 * PI * inner_err.get();
    }
    total.evals = inner_evals.get();
    total
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ cos θl dω_l = π over the hemisphere for every view: checks the horizon limit and
    /// the Jacobians of both warps (tolerance requested 1e-11; we allow 1e-10 for rounding
    /// of ~10⁴ terms).
    #[test]
    fn projected_solid_angle_is_pi() {
        for &mu in &[1.0, 0.7, 0.2, 0.01, 1e-4] {
            for warp in [
                LobeWarp::TanOverScale(0.3),
                LobeWarp::TanOverScale(1e-3),
                LobeWarp::Linear,
                LobeWarp::SheenFlank(1e-3),
                LobeWarp::SheenFlank(0.05),
            ] {
                let e = integrate_over_l(mu, warp, 1e-11, |n| [n.n_dot_l]);
                assert!(
                    (e.value[0] - PI).abs() < 1e-10,
                    "mu={mu} {warp:?}: {}",
                    e.value[0]
                );
            }
        }
    }

    /// At each kink one of the V-groove branches equals 1 exactly (2(n·h)(n·v) = v·h or
    /// 2(n·h)(n·l) = v·h) or the two branches are equal, to rounding (1e-13 relative: a few operations on O(1) numbers).
    #[test]
    fn vgroove_kinks_are_branch_switches() {
        let mut seen = [0usize; 3];
        for &mu in &[0.05f64, 0.3, 0.7, 0.95] {
            for k in 0..=32 {
                let phi = PI * k as f64 / 32.0;
                let s = (1.0 - mu * mu).sqrt();
                let psi = (s / mu * phi.cos()).atan();
                for th in vgroove_kinks(psi) {
                    let (sh, ch) = th.sin_cos();
                    let vh = s * sh * phi.cos() + mu * ch;
                    let nl = 2.0 * vh * ch - mu;
                    let (gv, gl) = (2.0 * ch * mu / vh, 2.0 * ch * nl / vh);
                    let which = [(gv - 1.0).abs(), (gl - 1.0).abs(), (gv - gl).abs()]
                        .iter()
                        .position(|&d| d < 1e-13);
                    let which = which.unwrap_or_else(|| {
                        panic!("mu={mu} phi={phi} th={th}: no branch switch, {gv} {gl}")
                    });
                    assert!(nl > 0.0 && th < tan_theta_h_max(s / mu, phi.cos()).atan());
                    seen[which] += 1;
                }
            }
        }
        assert!(seen.iter().all(|&n| n > 0), "{seen:?}");
    }

    #[test]
    fn horizon_limit_matches_geometry() {
        // at θh = θmax the reflected direction lies in the tangent plane
        for &(mu, phi) in &[(0.5f64, 0.3f64), (0.1, 2.0), (0.9, 1.5)] {
            let s = (1.0 - mu * mu).sqrt();
            let th = tan_theta_h_max(s / mu, phi.cos()).atan();
            let vh = s * th.sin() * phi.cos() + mu * th.cos();
            let nl = 2.0 * vh * th.cos() - mu;
            assert!(nl.abs() < 1e-14, "{nl}");
        }
    }
}
