//! The Schlick split sum of a rough dielectric interface: Blender EEVEE's `bsdf_ggx` (view
//! inside the denser medium, relative index η < 1) and `btdf_ggx` (view outside, η > 1).
//!
//! A real-time shader approximates the interface's Fresnel term by Schlick's
//! F = F0 + (F90 − F0)·s with F0 = ((1 − η)/(1 + η))² and the blend weight
//! s = (1 − cos θ_o)⁵, where θ_o is the angle to the micro-normal h **on the less dense side**
//! (Schlick 1994, eq. 24, writes F with the cosine of the larger of the two angles, the one
//! outside the denser medium): for η ≥ 1 the view's own c = v·h, for η < 1 the refracted
//! ray's cos θt = √(1 − (1 − c²)/η²) (Walter et al. 2007, eq. 40), and s = 1 under total
//! internal reflection (no cos θt: everything is reflected, F = F90). Splitting F out of the
//! interface's reflection and transmission albedos (`super::btdf`: R = ∫ w F G_r dω_h,
//! T = ∫ w (1 − F) G_t dω_h with w = D(h) c/(n·v) and G the masking–shadowing of the view
//! and the reflected or refracted direction) leaves three integrals independent of F0, F90:
//!
//! * `A = ∫ w (1 − s) G(v, l_r) [n·l_r > 0] dω_h`, the weight of F0 in the reflectance;
//! * `B = ∫ w s G(v, l_r) [n·l_r > 0] dω_h`, the weight of F90;
//! * `T = ∫ w (1 − s) G(v, l_t) [l_t exists, n·l_t < 0] dω_h`, the transmission factor,
//!
//! so that R = F0·A + F90·B and, with F90 = 1 (where 1 − F = (1 − F0)(1 − s)), the
//! transmittance is (1 − F0)·T: EEVEE's "reflectance = F0 * scale + F90 * bias,
//! transmittance = (1 - F0) * transmission_factor" (`eevee_lut_comp.glsl`, its
//! `ggx_bsdf_split_sum` and `ggx_btdf_gt_one`). With G = G1(v) G1(l) (separable Smith), w G1(v)
//! is the density of the visible normals, so each integral is the mean over visible normals
//! of (1 − s) G1(l) or s G1(l), as EEVEE's generator estimates it. T is a fraction of the
//! arriving flux (the radiance of the refracted light is not scaled by 1/η²). For η ≥ 1, A and
//! B do not depend on η (s = (1 − c)⁵ and l_r are the view's): they are the split sum of the
//! GGX BRDF, and EEVEE stores only T.
//!
//! In the smooth limit α → 0 (h = n, G → 1; `table::smooth`): A = 1 − s(μ), B = s(μ),
//! T = 1 − s(μ) with s at c = μ.

use super::btdf::{Facet, MicroNormal, SmithForm};
use super::ndf::Ndf;

/// Schlick's blend weight s = (1 − cos θ_o)⁵ of an interface of relative index `eta` at a
/// micro-normal with c = v·h: θ_o is the angle on the less dense side, the view's (c) for
/// η ≥ 1, the refracted ray's (cos θt) for η < 1; 1 under total internal reflection (see the
/// module doc).
#[inline]
pub fn outer_schlick_weight(eta: f64, c: f64) -> f64 {
    let cos_o = if eta >= 1.0 {
        c
    } else {
        let s2t = (1.0 - c * c) / (eta * eta);
        if s2t >= 1.0 {
            return 1.0;
        }
        (1.0 - s2t).sqrt()
    };
    (1.0 - cos_o.clamp(0.0, 1.0)).powi(5)
}

/// The `[A, B, T]` integrands per unit solid angle of micro-normal `m` for a view with
/// n·v = `n_dot_v`, G1(n·v) = `g1v`, relative index `eta` (module doc); 0 where h is not
/// visible or a direction does not exist or leaves on the wrong side.
#[inline]
pub fn integrands(
    ndf: &Ndf,
    smith: SmithForm,
    eta: f64,
    n_dot_v: f64,
    g1v: f64,
    m: &MicroNormal,
) -> [f64; 3] {
    let Some(f) = Facet::new(ndf, smith, n_dot_v, g1v, m) else {
        return [0.0; 3];
    };
    let s = outer_schlick_weight(eta, f.c);
    let gt = f
        .refraction(ndf, smith, g1v, eta, n_dot_v, m)
        .map_or(0.0, |(g, _)| g);
    [f.w * (1.0 - s) * f.gr, f.w * s * f.gr, f.w * (1.0 - s) * gt]
}

/// `[A, B, T]` of the smooth limit α = 0 at view cosine `mu` > 0 (module doc).
pub fn smooth_limit(eta: f64, mu: f64) -> [f64; 3] {
    let s = outer_schlick_weight(eta, mu);
    [1.0 - s, s, 1.0 - s]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// s at the two sides: η ≥ 1 uses c itself (Schlick's 5th power, exact at c = 0, 1);
    /// η < 1 uses cos θt (at c = 1, θt = 0 and s = 0; at the critical cosine c = √(1 − η²),
    /// cos θt = 0 and s = 1; below it, total internal reflection, s = 1); at η = 1 both
    /// sides agree (cos θt = c). Exact in f64 up to rounding (1e-15).
    #[test]
    fn weight_uses_the_cosine_on_the_less_dense_side() {
        assert_eq!(outer_schlick_weight(1.5, 1.0), 0.0);
        assert_eq!(outer_schlick_weight(1.5, 0.0), 1.0);
        assert!((outer_schlick_weight(1.5, 0.5) - 0.5f64.powi(5)).abs() < 1e-15);
        let eta: f64 = 0.6;
        assert!(outer_schlick_weight(eta, 1.0).abs() < 1e-15);
        let crit = (1.0 - eta * eta).sqrt();
        assert!((outer_schlick_weight(eta, crit) - 1.0).abs() < 1e-6);
        assert_eq!(outer_schlick_weight(eta, crit - 1e-3), 1.0);
        for c in [0.1, 0.5, 0.9] {
            let a = outer_schlick_weight(1.0, c);
            let b = outer_schlick_weight(1.0 - 1e-12, c);
            assert!((a - b).abs() < 1e-9, "c {c}: {a} vs {b}");
        }
        // negative control: the η < 1 weight is not the view's (1 − c)^5
        let c = 0.81;
        assert!((outer_schlick_weight(eta, c) - (1.0f64 - c).powi(5)).abs() > 0.1);
    }
}
