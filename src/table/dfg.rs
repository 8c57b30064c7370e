//! `dfg`: the split-sum tables of the specular lobe with the Fresnel factored out.
//!
//! With Schlick's F = F0 + (1 − F0)·Fc, Fc = (1 − v·h)⁵, the directional albedo is linear in
//! F0: E = F0·∫(1 − Fc) f cos + ∫ Fc f cos (Karis 2013, "Real Shading in Unreal Engine 4",
//! eq. 8), with f the BRDF at F = 1. Filament stores the same information as
//! (∫ Fc f cos, ∫ f cos) so that the second channel is the single-scattering albedo used for
//! multiple-scattering compensation (Filament documentation, "Energy loss in specular
//! reflectance"), and optionally the cloth albedo ∫ D_Charlie·V_Ashikhmin·cos in the third.

use super::albedo::brdfs_per_roughness;
use super::{DfgLayout, TableSpec, TexelResult};
use crate::integrate::dfg_kernel::{self, Column, Smith};
use crate::integrate::hemisphere::{integrate_over_l, Node};
use crate::integrate::tensor::integrate_over_l_smooth;
use crate::model::fresnel::schlick_weight;
use crate::model::{Fresnel, Masking, Ndf, NdfKind, Specular};

/// The split-sum pair at one (μ, α) with F = 1 inside `spec`: returns
/// `([∫(1−Fc) f cos, ∫ Fc f cos], errors, evaluations)`.
///
/// Smooth maskings use the fast tensor rule ([`integrate_over_l_smooth`], falling back to the
/// adaptive integrator per texel); the V-groove term's kinks go to the adaptive one directly.
pub fn split_sum(spec: &Specular, mu: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
    let g = |n: &Node| {
        let f = spec.cosine_weighted_with(n, 1.0);
        let fc = schlick_weight(n.v_dot_h);
        [f * (1.0 - fc), f * fc]
    };
    let e = if spec.masking == Masking::VGroove {
        integrate_over_l(mu, spec.warp(), tol, g)
    } else {
        integrate_over_l_smooth(mu, Some(&spec.ndf), tol, g)
    };
    (e.value, e.error, e.evals)
}

/// [`split_sum`] by the adaptive integrator alone (the reference the fast path is tested
/// against).
pub fn split_sum_adaptive(spec: &Specular, mu: f64, tol: f64) -> ([f64; 2], [f64; 2], u64) {
    let e = integrate_over_l(mu, spec.warp(), tol, |n| {
        let f = spec.cosine_weighted_with(n, 1.0);
        let fc = schlick_weight(n.v_dot_h);
        [f * (1.0 - fc), f * fc]
    });
    (e.value, e.error, e.evals)
}

/// The sheen albedo ∫ D_Charlie(α)·V_Ashikhmin·(n·l) dω_l at one (μ, α).
pub fn sheen_albedo(alpha: f64, mu: f64, tol: f64) -> (f64, f64, u64) {
    let sheen = Specular {
        ndf: Ndf::new(NdfKind::Charlie, alpha).expect("alpha validated > 0"),
        masking: Masking::Ashikhmin,
        fresnel: Fresnel::None,
    };
    let e = integrate_over_l_smooth(mu, Some(&sheen.ndf), tol, |n| [sheen.cosine_weighted(n)]);
    (e.value[0], e.error[0], e.evals)
}

/// [`sheen_albedo`] by the adaptive integrator alone.
pub fn sheen_albedo_adaptive(alpha: f64, mu: f64, tol: f64) -> (f64, f64, u64) {
    let sheen = Specular {
        ndf: Ndf::new(NdfKind::Charlie, alpha).expect("alpha validated > 0"),
        masking: Masking::Ashikhmin,
        fresnel: Fresnel::None,
    };
    let e = integrate_over_l(mu, sheen.ndf.warp(), tol, |n| [sheen.cosine_weighted(n)]);
    (e.value[0], e.error[0], e.evals)
}

/// The Smith form the specialised kernel handles for this lobe, if it does (GGX with
/// Smith masking; the split sums ignore the lobe's own Fresnel).
fn kernel_smith(s: &Specular) -> Option<Smith> {
    match (s.ndf.kind(), s.masking) {
        (NdfKind::Ggx, Masking::SmithHeightCorrelated) => Some(Smith::HeightCorrelated),
        (NdfKind::Ggx, Masking::SmithSeparable) => Some(Smith::Separable),
        _ => None,
    }
}

/// Whether a dfg table with this model uses the specialised kernels of
/// [`dfg_kernel`] (first) for its split-sum channels.
pub fn uses_kernel(ndf: Option<NdfKind>, masking: Masking) -> bool {
    ndf == Some(NdfKind::Ggx)
        && matches!(
            masking,
            Masking::SmithHeightCorrelated | Masking::SmithSeparable
        )
}

/// [`split_sum`] through the specialised GGX kernel where it applies, with the view setup
/// of `col` (whose μ must be `mu`); the generic path where it does not apply or its
/// estimate does not reach `tol` (the kernel's evaluations are counted either way).
pub fn split_sum_column(
    spec: &Specular,
    col: &Column,
    mu: f64,
    tol: f64,
) -> ([f64; 2], [f64; 2], u64) {
    let mut spent = 0;
    if let Some(smith) = kernel_smith(spec) {
        match dfg_kernel::ggx_split_sum(col, spec.ndf.alpha(), smith, tol) {
            Ok(e) => return (e.value, e.error, e.evals),
            Err(n) => spent = n,
        }
    }
    let (v, e, n) = split_sum(spec, mu, tol);
    (v, e, n + spent)
}

/// [`sheen_albedo`] through the specialised cloth kernel first (see [`split_sum_column`]).
pub fn sheen_albedo_column(alpha: f64, col: &Column, mu: f64, tol: f64) -> (f64, f64, u64) {
    match dfg_kernel::charlie_sheen(col, alpha, tol) {
        Ok(e) => (e.value[0], e.error[0], e.evals),
        Err(spent) => {
            let (v, e, n) = sheen_albedo(alpha, mu, tol);
            (v, e, n + spent)
        }
    }
}

pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let brdfs = brdfs_per_roughness(spec);
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    let layout = spec.dfg_layout.expect("validated");
    let cloth = spec.cloth;
    // the view setup of each column, built by whichever thread needs it first (a pure
    // function of μ, so the result does not depend on which)
    let columns: Vec<std::sync::OnceLock<Column>> = (0..axes[0].size)
        .map(|_| std::sync::OnceLock::new())
        .collect();
    Box::new(move |idx| {
        let mu = axes[0].coord(idx[0]);
        let col = columns[idx[0]].get_or_init(|| Column::new(mu));
        let s = brdfs[idx[1]]
            .specular
            .as_ref()
            .expect("validated: dfg has an NDF");
        // each channel of the pair below is a sum/difference of the two integrals, so its
        // error bound is the sum of theirs
        let ([a, b], [ea, eb], n) = split_sum_column(s, col, mu, tol);
        let mut r = match layout {
            DfgLayout::Karis => TexelResult {
                value: vec![a, b],
                error: vec![ea, eb],
                evals: n,
            },
            DfgLayout::Filament => TexelResult {
                value: vec![b, a + b],
                error: vec![eb, ea + eb],
                evals: n,
            },
        };
        if cloth {
            let alpha = axes[1].alpha(idx[1]).expect("roughness axis");
            let (v, e, n) = sheen_albedo_column(alpha, col, mu, tol);
            r.value.push(v);
            r.error.push(e);
            r.evals += n;
        }
        r
    })
}
