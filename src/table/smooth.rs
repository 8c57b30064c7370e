//! The smooth-surface limit α = 0, in closed form: the texels of a roughness axis that
//! starts (or ends) at α = 0, as EEVEE's, Cycles' and BSDL's tables do.
//!
//! As α → 0 every microfacet NDF concentrates on h = n (a Dirac delta in the projected
//! solid angle, `∫ D (n·h) dω_h = 1`), so the specular lobe becomes the mirror: `l` is the
//! reflection of `v`, `n·l = n·v = μ`, `v·h = μ`, and
//! `∫ f (n·l) dω_l = F(μ)·G(v, l_mirror)`. Smith's Λ vanishes for μ > 0 (`Λ_GGX = (−1 +
//! √(1 + α² tan²θ))/2`, `Λ_Beckmann ≤ e^{−a²}/(2a√π)` with a = 1/(α tan θ)), so G → 1; the
//! V-groove term at h = n is `min(1, 2μ/μ) = 1`. Hence, for μ > 0:
//!
//! * albedo `E = F(μ) + w_d` (the Lambertian lobe's albedo is its weight w_d);
//! * split sum (Karis) `A = 1 − (1 − μ)⁵`, `B = (1 − μ)⁵`; (Filament) `R = (1 − μ)⁵`, `G = 1`;
//! * Kulla–Conty `E = 1`, `E_avg = 1`; `albedo-fresnel` `E = F_p(μ)` of the slice's Fresnel;
//! * the smooth dielectric interface `R = F(μ; η)`, `T = 1 − R` (total internal reflection
//!   included in F), so `E = R + T = 1` and `E_avg = 1`;
//! * the generalized-Schlick averages `S_vndf = S_albedo = s(μ)` (h = n);
//! * the Schlick split sum of a dielectric `A = 1 − s`, `B = s`, `T = 1 − s` with Schlick's
//!   weight s on the less dense side at h = n (`model::schlick_dielectric`);
//! * Smith `G1 = 1`, `G2 = 1` (0 where a cosine is 0: Λ(0) = ∞ for every α > 0); the same
//!   for Schlick-GGX with `k = α/2` (`G1 = μ/(μ(1 − k) + k) → 1`); Schlick-GGX with
//!   Karis' direct-light `k = (√α + 1)²/8 → 1/8`: `G1(μ) = μ/(7μ/8 + 1/8)`, so the mirror
//!   lobe carries `G1(μ)²` (`E = F(μ) G1(μ)²`, `A = (1 − (1 − μ)⁵) G1(μ)²`, …) and
//!   `G2 = G1(n·v) G1(n·l)`;
//! * `E_avg = 2∫₀¹ E(μ) μ dμ` of the limit E, by adaptive Gauss–Kronrod.
//!
//! The sheen NDF (Charlie) has no mirror limit (its lobe concentrates at grazing half
//! vectors) and a distribution table (`ndf`) would hold a delta: both refuse α = 0. The
//! tests (`tests/smooth_limit.rs`) check that the integrals at α → 0 approach these values.

use super::spec::{DfgLayout, TableKind, TableSpec};
use super::texel::TexelResult;
use crate::model::masking::SchlickGgx;
use crate::model::{Fresnel, Masking, NdfKind};
use crate::quadrature::{integrate1, Tolerance};

/// Whether the spec's kind and model have a smooth limit; the message says why not.
pub(crate) fn supported(spec: &TableSpec) -> Result<(), String> {
    let why = match spec.kind {
        TableKind::Ndf => Some("D at alpha = 0 is a Dirac delta, which no texel can hold"),
        TableKind::Vgroove => None,
        TableKind::ClassicAlbedo | TableKind::ClassicAlbedoAniso => {
            Some("the classic models' parameters are not an NDF's alpha")
        }
        TableKind::Ltc | TableKind::LtcSphere => Some(
            "the lobe at alpha = 0 is a mirror, which no LTC holds; clamp the roughness axis' values (Heitz's tables: alpha >= 1e-5)",
        ),
        _ if spec.model.ndf == Some(NdfKind::Charlie) => Some(
            "the charlie sheen NDF has no smooth limit (its lobe concentrates at grazing half vectors)",
        ),
        TableKind::Dfg if spec.cloth => Some(
            "the cloth channel's charlie sheen NDF has no smooth limit (its lobe concentrates at grazing half vectors)",
        ),
        _ => None,
    };
    match why {
        Some(w) => Err(format!(
            "a {} table of this model has no value at alpha = 0 ({w})",
            spec.kind.name()
        )),
        None => Ok(()),
    }
}

/// The masking term at the mirror configuration of α = 0 (n·h = 1, v·h = n·l = n·v = μ).
fn mirror_g(masking: Masking, mu: f64) -> f64 {
    g2_at_zero(masking, mu, mu)
}

/// The masking term G2(n·v, n·l) at α = 0, for the terms that are functions of the two
/// cosines (and 1 for the V-groove term at h = n).
fn g2_at_zero(masking: Masking, v: f64, l: f64) -> f64 {
    let above = |x: f64| if x > 0.0 { 1.0 } else { 0.0 };
    match masking {
        Masking::None | Masking::VGroove => 1.0,
        // Λ → 0 above the horizon; Schlick's G1 with k = α/2 → 0 is μ/μ = 1
        Masking::SmithSeparable | Masking::SmithHeightCorrelated | Masking::SchlickGgx => {
            above(v) * above(l)
        }
        // k = (√α + 1)²/8 → 1/8: G1(μ) = μ/(μ·7/8 + 1/8), G1² at the mirror
        Masking::SchlickGgxDirect => {
            let s = SchlickGgx::direct(0.0);
            s.g1(v) * s.g1(l)
        }
        // (Charlie only, refused by `supported`)
        Masking::Ashikhmin => {
            let d = v + l - v * l;
            if d > 0.0 {
                v * l / d
            } else {
                0.0
            }
        }
        Masking::ContyKulla | Masking::ContyKullaSoftened => 0.0,
    }
}

/// E(μ) of the smooth limit with Fresnel term `fresnel`: the mirror lobe plus the diffuse
/// lobe's albedo.
fn albedo(spec: &TableSpec, fresnel: Fresnel, mu: f64) -> f64 {
    let m = &spec.model;
    let spec_part = if m.ndf.is_some() {
        fresnel.eval(mu) * mirror_g(m.masking, mu)
    } else {
        0.0
    };
    spec_part + m.diffuse_weight
}

/// `2∫₀¹ E(μ) μ dμ` of the smooth limit, with its error estimate.
fn average(spec: &TableSpec, fresnel: Fresnel) -> (f64, f64) {
    let tol = Tolerance {
        abs: 0.5 * spec.tolerance,
        ..Default::default()
    };
    let (v, e) = integrate1(|mu| 2.0 * mu * albedo(spec, fresnel, mu), 0.0, 1.0, tol);
    (v, e)
}

/// The values of texel `idx` (whose roughness texel is at α = 0).
pub(crate) fn texel(spec: &TableSpec, idx: [usize; 3]) -> TexelResult {
    let m = &spec.model;
    let mu = || spec.axes[0].coord(idx[0]);
    // the view cosine of a dielectric kind
    let view = || super::dielectric::view_cosine(spec, idx[0], idx[2]);
    let schlick = |mu: f64| crate::model::fresnel::schlick_weight(mu);
    match spec.kind {
        TableKind::Albedo => TexelResult::exact(vec![albedo(spec, m.fresnel, mu())]),
        TableKind::AlbedoAvg => {
            let (v, e) = average(spec, m.fresnel);
            TexelResult {
                value: vec![v],
                error: vec![e],
                evals: 0,
            }
        }
        TableKind::KullaConty => {
            let (v, e) = average(spec, Fresnel::None);
            TexelResult {
                value: vec![albedo(spec, Fresnel::None, mu()), v],
                error: vec![0.0, e],
                evals: 0,
            }
        }
        TableKind::AlbedoFresnel => {
            let f = super::energy::fresnel_of_slice(spec, idx[2]);
            TexelResult::exact(vec![albedo(spec, f, mu())])
        }
        TableKind::DielectricBtdf => {
            let eta = super::dielectric::eta_of_slice(spec, idx[2]);
            let r = crate::model::fresnel::dielectric(view(), eta);
            TexelResult::exact(vec![r, 1.0 - r])
        }
        // R + T = F + (1 − F) for μ > 0 (validation keeps μ > 0)
        TableKind::DielectricAlbedo => TexelResult::exact(vec![1.0]),
        TableKind::DielectricAlbedoAvg => TexelResult::exact(vec![1.0]),
        TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => {
            super::schlick_weight::smooth_texel(spec, idx)
        }
        TableKind::DielectricSchlick => super::dielectric_schlick::smooth_texel(spec, idx),
        TableKind::Dfg => {
            let mu = mu();
            let g = mirror_g(m.masking, mu);
            let fc = schlick(mu);
            TexelResult::exact(match spec.dfg_layout {
                Some(DfgLayout::Karis) => vec![(1.0 - fc) * g, fc * g],
                Some(DfgLayout::KarisF82) => vec![
                    (1.0 - fc) * g,
                    fc * g,
                    crate::model::fresnel::f82_tint_weight(mu) * g,
                ],
                _ => vec![fc * g, g],
            })
        }
        TableKind::G1 => TexelResult::exact(vec![mirror_g(m.masking, mu())]),
        TableKind::G2 => {
            let (v, l) = (mu(), spec.axes[1].coord(idx[1]));
            TexelResult::exact(vec![g2_at_zero(m.masking, v, l)])
        }
        TableKind::Ndf
        | TableKind::Vgroove
        | TableKind::ClassicAlbedo
        | TableKind::ClassicAlbedoAniso
        | TableKind::Ltc
        | TableKind::LtcSphere => {
            unreachable!("refused by smooth::supported")
        }
    }
}
