//! `dielectric-schlick`: the Schlick split sum of a rough dielectric interface over
//! (cos θv; roughness; η), 3D, channels A, B, T (the integrands and what they mean are in
//! [`crate::model::schlick_dielectric`]): R = F0·A + F90·B, transmittance (1 − F0)·T, with
//! Schlick's weight taken on the less dense side. Blender EEVEE's `bsdf_ggx` (η < 1, its
//! critical-angle view axis: all three channels) and `btdf_ggx` (η > 1: T alone, stored
//! through the preset's `channels`).
//!
//! Every texel by its own nested rule over micro-normals
//! ([`crate::kernels::micro_normals`]) with the standard panel boundaries of its η (the
//! reflected horizon; for η < 1 the critical angle, where cos θt and so s have a square-root
//! end, and the transmitted horizon): the same breakpoints as `dielectric-btdf`, whose
//! integrands have the same kinks. Validation is the dielectric kinds' (`dielectric.rs`:
//! GGX, Smith masking, an η axis, views above the horizon; a critical-angle view axis).

use super::dielectric::{eta_of_slice, smith_of, view_cosine};
use super::{TableSpec, TexelResult};
use crate::kernels::micro_normals::{integrate_micro_normals, Rule};
use crate::lut::Channel;
use crate::model::btdf::MicroNormal;
use crate::model::schlick_dielectric::{integrands, smooth_limit};
use crate::model::{Ndf, NdfKind};

fn ch(name: &str, meaning: &str) -> Channel {
    Channel {
        name: name.into(),
        meaning: meaning.into(),
    }
}

/// The three channels.
pub(crate) fn channels(_spec: &TableSpec) -> Vec<Channel> {
    vec![
        ch(
            "A",
            "A = int w (1 - s) G(v, l_r) dw_h (w = D c/(n.v), s = (1 - cos theta_o)^5 with theta_o the angle to h on the less dense side: v.h for eta >= 1, the refracted ray's for eta < 1, s = 1 under total internal reflection): the weight of F0 in the reflectance (EEVEE's scale)",
        ),
        ch(
            "B",
            "B = int w s G(v, l_r) dw_h: the weight of F90 in the reflectance (EEVEE's bias)",
        ),
        ch(
            "T",
            "T = int w (1 - s) G(v, l_t) dw_h over the refracted directions below the surface: the transmission factor, transmittance = (1 - F0) T (EEVEE's transmission_factor; a fraction of the arriving flux, radiance not scaled by 1/eta^2)",
        ),
    ]
}

pub(crate) fn reconstruction(_spec: &TableSpec) -> &'static str {
    "Schlick's Fresnel of a dielectric of relative index eta, F = F0 + (F90 - F0) s with F0 = ((1 - eta)/(1 + eta))^2 and \
     s = (1 - cos theta_o)^5 on the less dense side: reflectance = F0 A + F90 B, transmittance = (1 - F0) T (F90 = 1). \
     For eta >= 1, A and B are the GGX BRDF's split sum (independent of eta); for eta < 1 the view is inside the denser \
     medium and B includes total internal reflection."
}

/// One texel's `[A, B, T]` by its own rule.
pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let tol = spec.tolerance;
    let smith = smith_of(spec);
    let kind = spec.model.ndf.unwrap_or(NdfKind::Ggx);
    let ndfs: Vec<Ndf> = (0..spec.axes[1].size)
        .map(|j| Ndf::new(kind, spec.axes[1].alpha(j).expect("roughness axis")).expect("validated"))
        .collect();
    let nz = spec.axes[2].size;
    let etas: Vec<f64> = (0..nz).map(|z| eta_of_slice(spec, z)).collect();
    let mus: Vec<Vec<f64>> = (0..spec.axes[0].size)
        .map(|i| (0..nz).map(|z| view_cosine(spec, i, z)).collect())
        .collect();
    Box::new(move |idx| {
        let (ndf, eta, mu) = (&ndfs[idx[1]], etas[idx[2]], mus[idx[0]][idx[2]]);
        let mu1 = mu.min(1.0);
        let g1v = ndf.g1(mu1);
        let e = integrate_micro_normals(ndf, Rule::standard(&[eta]), mu, tol, |h: &MicroNormal| {
            integrands(ndf, smith, eta, mu1, g1v, h)
        });
        TexelResult {
            value: e.value.to_vec(),
            error: e.error.to_vec(),
            evals: e.evals,
        }
    })
}

/// The smooth limit α = 0 of texel `idx` (`table::smooth`).
pub(crate) fn smooth_texel(spec: &TableSpec, idx: [usize; 3]) -> TexelResult {
    let eta = eta_of_slice(spec, idx[2]);
    let mu = view_cosine(spec, idx[0], idx[2]);
    TexelResult::exact(smooth_limit(eta, mu).to_vec())
}
