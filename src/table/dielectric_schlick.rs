//! `dielectric-schlick`: the Schlick split sum of a rough dielectric interface over
//! (cos θv; roughness; η), 3D, channels A, B, T (the integrands and what they mean are in
//! [`crate::model::schlick_dielectric`]): R = F0·A + F90·B, transmittance (1 − F0)·T, with
//! Schlick's weight taken on the less dense side. Blender EEVEE's `bsdf_ggx` (η < 1, its
//! critical-angle view axis: all three channels) and `btdf_ggx` (η > 1: T alone, stored
//! through the preset's `channels`).
//!
//! Every texel by a nested rule over micro-normals ([`crate::kernels::micro_normals`]) with
//! the standard panel boundaries of its η (the reflected horizon; for η < 1 the critical
//! angle, where cos θt and so s have a square-root end, and the transmitted horizon): the
//! same breakpoints as `dielectric-btdf`, whose integrands have the same kinks. An η < 1
//! texel has a rule of its own. The η ≥ 1 texels of one fibre (one roughness and view
//! cosine, every η) share one: for η ≥ 1 their breakpoints are the same, s = (1 − v·h)⁵ and
//! so A and B do not depend on η, and only the refracted direction's masking in T does, so
//! up to [`FIBRE_SLICES`] slices are the channels [A, B, T₁, T₂, …] of one rule (each slice's
//! value and estimate are its channels' own; the rule refines until every channel meets the
//! tolerance). Validation is the dielectric kinds' (`dielectric.rs`: GGX, Smith masking, an
//! η axis, views above the horizon; a critical-angle view axis).

use super::dielectric::{
    eta_of_slice, etas_and_mus, fibre_groups_of, ndfs, roughness_fibres_with, smith_of, view_cosine,
};
use super::{TableSpec, TexelResult};
use crate::kernels::micro_normals::{integrate_micro_normals, Rule};
use crate::kernels::roughness_fibre::ROUGHNESS_FIBRE;
use crate::lut::Channel;
use crate::model::btdf::{Facet, GgxRefractions, MicroNormal, SmithForm};
use crate::model::schlick_dielectric::{integrands, outer_schlick_weight, smooth_limit};
use crate::model::Ndf;

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

/// Most η ≥ 1 slices one rule of a fibre serves: channels A, B and one T per slice. Measured
/// on `eevee-btdf-ggx` (64 slices, all η > 1; the sidecars' evaluations): 2,590 nodes per rule
/// of 8 slices against 2,581 per texel alone, so 8× fewer nodes, each with 8 refractions;
/// the bake took 1.14 s instead of 3.43 s (2 threads, 2026-12-02).
pub const FIBRE_SLICES: usize = 8;

/// Channels of one shared rule.
const FIBRE_CHANNELS: usize = 2 + FIBRE_SLICES;

/// `[A, B, T]` of one texel (η, view cosine `mu`) by its own rule.
fn texel(ndf: &Ndf, smith: SmithForm, eta: f64, mu: f64, tol: f64) -> TexelResult {
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
}

/// `[A, B, T₁, …, T_k]` of the relative indices `etas` (all ≥ 1, at most [`FIBRE_SLICES`])
/// at one view cosine `mu`, by one rule: per micro-normal the facet's weight, masking and s
/// once, the refraction once per index.
fn shared(
    ndf: &Ndf,
    smith: SmithForm,
    etas: &[f64],
    mu: f64,
    tol: f64,
) -> crate::quadrature::Estimate<FIBRE_CHANNELS> {
    debug_assert!(etas.len() <= FIBRE_SLICES && etas.iter().all(|&e| e >= 1.0));
    let mu1 = mu.min(1.0);
    let g1v = ndf.g1(mu1);
    let refractions = GgxRefractions::<FIBRE_SLICES>::new(ndf, smith, g1v, mu1, etas);
    integrate_micro_normals(ndf, Rule::standard(etas), mu, tol, |h: &MicroNormal| {
        let mut y = [0.0; FIBRE_CHANNELS];
        let Some(f) = Facet::new(ndf, smith, mu1, g1v, h) else {
            return y;
        };
        // (η ≥ 1: the weight takes the view's angle, the same for every index)
        let s = outer_schlick_weight(1.0, f.c);
        let wt = f.w * (1.0 - s);
        y[0] = wt * f.gr;
        y[1] = f.w * s * f.gr;
        // (lanes beyond the indices repeat the last: dropped)
        let g = refractions.g(&f, h);
        for (t, &g) in y[2..].iter_mut().zip(&g).take(etas.len()) {
            *t = wt * g;
        }
        y
    })
}

/// One texel's `[A, B, T]` by its own rule (the texel-by-texel path, and `readback`'s exact
/// values).
pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let tol = spec.tolerance;
    let smith = smith_of(spec);
    let ndfs = ndfs(spec);
    let (etas, mus) = etas_and_mus(spec);
    Box::new(move |idx| texel(&ndfs[idx[1]], smith, etas[idx[2]], mus[idx[0]][idx[2]], tol))
}

/// The fibre path ([`super::FibreFn`]): every η ≥ 1 slice of one (view texel, roughness),
/// those with the same view cosine in shared rules of up to [`FIBRE_SLICES`]
/// ([`fibre_groups_of`]); evaluations counted at each group's first slice. The η < 1 slices
/// are left to [`roughness_fibres`].
pub(crate) fn fibre_fn(spec: &TableSpec) -> super::FibreFn {
    let tol = spec.tolerance;
    let smith = smith_of(spec);
    let ndfs = ndfs(spec);
    let (etas, mus) = etas_and_mus(spec);
    Box::new(move |i, j| {
        let (ndf, mus) = (&ndfs[j], &mus[i]);
        let mut out = vec![TexelResult::exact(vec![0.0; 3]); etas.len()];
        for g in fibre_groups_of(&etas, mus, FIBRE_SLICES) {
            if let [z] = g[..] {
                if etas[z] >= 1.0 {
                    out[z] = texel(ndf, smith, etas[z], mus[z], tol);
                }
                continue;
            }
            let group: Vec<f64> = g.iter().map(|&z| etas[z]).collect();
            let e = shared(ndf, smith, &group, mus[g[0]], tol);
            for (k, &z) in g.iter().enumerate() {
                out[z] = TexelResult {
                    value: vec![e.value[0], e.value[1], e.value[2 + k]],
                    error: vec![e.error[0], e.error[1], e.error[2 + k]],
                    evals: if k == 0 { e.evals } else { 0 },
                };
            }
        }
        out
    })
}

/// The roughness-fibre path ([`super::RoughnessFibres`]): every η < 1 slice's texels at one
/// view texel by [`roughness_fibres_with`] (`dielectric.rs`).
pub(crate) fn roughness_fibres(spec: &TableSpec) -> super::RoughnessFibres {
    // A, B, T = (1 − s) w_r, s w_r, (1 − s) w_t (`integrands`)
    roughness_fibres_with::<{ 3 * ROUGHNESS_FIBRE }, 3>(spec, |eta, c| {
        let s = outer_schlick_weight(eta, c);
        [[1.0 - s, 0.0], [s, 0.0], [0.0, 1.0 - s]]
    })
}

/// The smooth limit α = 0 of texel `idx` (`table::smooth`).
pub(crate) fn smooth_texel(spec: &TableSpec, idx: [usize; 3]) -> TexelResult {
    let eta = eta_of_slice(spec, idx[2]);
    let mu = view_cosine(spec, idx[0], idx[2]);
    TexelResult::exact(smooth_limit(eta, mu).to_vec())
}
