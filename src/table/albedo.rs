//! `albedo` and `albedo-avg`: directional albedo E(μ) = ∫ f(v, l)(n·l) dω_l of the model's
//! BRDF (its own Fresnel, its diffuse lobe), and its cosine-weighted average
//! E_avg = 2∫₀¹ E(μ) μ dμ (Kulla & Conty 2017, the input of their energy compensation).

use super::methods::{
    albedo_uses_kernel, charlie_kernels, charlie_polar, kernel_smith, vgroove_fast_path,
};
use super::texel::brdfs_per_roughness;
use super::{TableKind, TableSpec, TexelResult};
use crate::hemisphere::tensor::integrate_over_l_smooth;
use crate::hemisphere::{integrate_over_l, LobeWarp};
use crate::kernels::sheen_azimuth::View;
use crate::kernels::vgroove::{beckmann_vgroove_albedo, integrate_over_l_kinked, TailCut};
use crate::model::{Brdf, Masking};
use crate::quadrature::budget::{with_budget, INTEGRAL_EVAL_BUDGET};
use crate::quadrature::{integrate, Tolerance};

/// E(μ) for one BRDF, to absolute tolerance `tol`. Returns `([value], [error], evaluations)`.
///
/// GGX with Smith masking and Charlie with Ashikhmin's visibility (F = 1, no diffuse lobe,
/// see [`albedo_uses_kernel`]) use their specialised kernels first (GGX: the 1D polar one,
/// [`ggx_polar`](crate::kernels::ggx_polar); Charlie: the θh cloth kernel, `charlie_kernels`); other smooth
/// models, and texels where a kernel's estimate does not reach the tolerance, the fast tensor
/// rule ([`integrate_over_l_smooth`], falling back to the adaptive integrator per texel); the
/// V-groove term's kinks go to its branch-split rule
/// ([`vgroove`](crate::kernels::vgroove)), then the adaptive integrator.
pub fn directional_albedo(brdf: &Brdf, mu: f64, tol: f64) -> ([f64; 1], [f64; 1], u64) {
    directional_albedo_in(brdf, mu, tol, None)
}

/// [`directional_albedo`] with, for the cloth kernels, the view data and shared node data
/// of a table column (`view.mu()` must be `mu`): the same result, bit for bit (every shared
/// entry is a pure function of μ and its node).
fn directional_albedo_in(
    brdf: &Brdf,
    mu: f64,
    tol: f64,
    view: Option<&View>,
) -> ([f64; 1], [f64; 1], u64) {
    let kinked = brdf
        .specular
        .as_ref()
        .is_some_and(|s| s.masking == Masking::VGroove);
    if kinked {
        let s = brdf.specular.as_ref().expect("kinked");
        let Some(tail) = vgroove_fast_path(s, brdf.diffuse_weight, tol) else {
            return directional_albedo_adaptive(brdf, mu, tol);
        };
        let mut spent = 0;
        // a Beckmann lobe alone: the closed-form piece integrand (the tail cut is its sign)
        if s.ndf.kind() == crate::model::NdfKind::Beckmann && tail != TailCut::NONE && mu > 0.0 {
            use crate::model::fresnel::{dielectric_one_division, Fresnel};
            let alpha = s.ndf.alpha();
            // (inside the kernel 0 < v·h ≤ 1; η ≥ 1 here: vgroove_fast_path refuses η < 1)
            let r = match s.fresnel {
                Fresnel::Dielectric { eta } if eta >= 1.0 => {
                    let f = |c: f64| dielectric_one_division(c.clamp(0.0, 1.0), eta);
                    beckmann_vgroove_albedo(mu, alpha, tail, tol, f)
                }
                fr => beckmann_vgroove_albedo(mu, alpha, tail, tol, |c: f64| fr.eval(c)),
            };
            match r {
                Ok(e) => return (e.value, e.error, e.evals),
                Err(n) => spent = n,
            }
        }
        let mut e = integrate_over_l_kinked(mu, s.warp(), tail, tol, |n| {
            [s.cosine_weighted(n) + brdf.diffuse_cosine_weighted(n)]
        });
        e.evals += spent;
        return (e.value, e.error, e.evals);
    }
    let mut spent = 0;
    // GGX + Smith with Schlick's Fresnel and no diffuse lobe: F is linear in F0, so
    // E = F0·A + B with A, B the split-sum channels (Karis 2013, eq. 8), each to tol/2
    if let Some(s) = brdf
        .specular
        .as_ref()
        .filter(|_| brdf.diffuse_weight == 0.0 && mu > 0.0)
    {
        if let (crate::model::Fresnel::Schlick { f0 }, Some(smith)) = (s.fresnel, kernel_smith(s)) {
            if f0.abs() <= 1.0 {
                match crate::kernels::ggx_polar::ggx_split_sum(mu, s.ndf.alpha(), smith, 0.5 * tol)
                {
                    Ok(e) => {
                        return (
                            [f0 * e.value[0] + e.value[1]],
                            [f0.abs() * e.error[0] + e.error[1]],
                            e.evals,
                        )
                    }
                    Err(n) => spent = n,
                }
            }
        }
    }
    // GGX + Smith and Charlie + Ashikhmin lobes with F = 1 and no diffuse lobe: the
    // specialised kernels first (E = A + B of the split sum, errors added)
    if let Some(s) = brdf.specular.as_ref().filter(|s| {
        brdf.diffuse_weight == 0.0 && s.fresnel == crate::model::Fresnel::None && mu > 0.0
    }) {
        use crate::model::NdfKind;
        if let Some(smith) = kernel_smith(s) {
            match crate::kernels::ggx_polar::ggx_albedo(mu, s.ndf.alpha(), smith, tol) {
                Ok(e) => return (e.value, e.error, e.evals + spent),
                Err(n) => spent += n,
            }
        } else if let Some(r) = match view {
            Some(v) => charlie_polar(s, v, tol),
            None => charlie_polar(s, &View::new(mu), tol),
        } {
            match r {
                Ok(e) => return (e.value, e.error, e.evals),
                Err(n) => spent = n,
            }
        } else if (s.ndf.kind(), s.masking) == (NdfKind::Charlie, Masking::Ashikhmin) {
            let r = match view {
                Some(v) => charlie_kernels(v, s.ndf.alpha(), tol),
                None => charlie_kernels(&View::new(mu), s.ndf.alpha(), tol),
            };
            match r {
                Ok(e) => return (e.value, e.error, e.evals),
                Err(n) => spent = n,
            }
        }
    }
    let e = integrate_over_l_smooth(mu, brdf.specular.as_ref().map(|s| &s.ndf), tol, |n| {
        let s = brdf.specular.as_ref().map_or(0.0, |s| s.cosine_weighted(n));
        [s + brdf.diffuse_cosine_weighted(n)]
    });
    (e.value, e.error, e.evals + spent)
}

/// Whether an albedo table is baked column by column ([`column_fn`]): Charlie/Ashikhmin
/// lobes with F = 1 and no diffuse lobe, whose cloth kernels share node data between the
/// roughnesses of a column (one view μ).
pub(crate) fn by_column(spec: &TableSpec) -> bool {
    use crate::model::NdfKind;
    spec.kind == TableKind::Albedo
        && albedo_uses_kernel(&spec.model)
        && spec.model.ndf == Some(NdfKind::Charlie)
}

/// The texels of one column (one view μ, every roughness, in axis-1 order) of a table for
/// which [`by_column`] holds: the view data ([`Column`]) and the cloth kernels' shared node
/// data ([`SheenCache`]) built once for the column; each value is the same, bit for bit,
/// as [`texel_fn`] computes it alone.
pub(crate) fn column_fn(spec: &TableSpec) -> Box<dyn Fn(usize) -> Vec<TexelResult> + Sync> {
    let brdfs = brdfs_per_roughness(spec);
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    Box::new(move |i0| {
        let mu = axes[0].coord(i0);
        let view = View::new(mu);
        brdfs
            .iter()
            .map(|b| {
                let (v, e, n) = if mu > 0.0 {
                    directional_albedo_in(b, mu, tol, Some(&view))
                } else {
                    directional_albedo(b, mu, tol)
                };
                TexelResult {
                    value: v.to_vec(),
                    error: e.to_vec(),
                    evals: n,
                }
            })
            .collect()
    })
}

/// [`directional_albedo`] by the adaptive integrator alone.
pub fn directional_albedo_adaptive(brdf: &Brdf, mu: f64, tol: f64) -> ([f64; 1], [f64; 1], u64) {
    let warp = brdf
        .specular
        .as_ref()
        .map_or(LobeWarp::TanOverScale(1.0), |s| s.warp());
    let e = integrate_over_l(mu, warp, tol, |n| {
        let s = brdf.specular.as_ref().map_or(0.0, |s| s.cosine_weighted(n));
        [s + brdf.diffuse_cosine_weighted(n)]
    });
    (e.value, e.error, e.evals)
}

pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let brdfs = brdfs_per_roughness(spec);
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    match spec.kind {
        TableKind::Albedo => Box::new(move |idx| {
            let (v, e, n) = directional_albedo(&brdfs[idx[1]], axes[0].coord(idx[0]), tol);
            TexelResult {
                value: v.to_vec(),
                error: e.to_vec(),
                evals: n,
            }
        }),
        TableKind::AlbedoAvg => Box::new(move |idx| {
            let (v, e, n) = average_albedo(&brdfs[idx[0]], tol);
            TexelResult {
                value: vec![v],
                error: vec![e],
                evals: n,
            }
        }),
        _ => unreachable!(),
    }
}

/// E_avg = 2∫₀¹ E(μ) μ dμ: adaptive Gauss–Kronrod over μ (half the budget) of the nested
/// hemisphere integral (a quarter; its error enters as 2∫ err·μ dμ ≤ err). The inner
/// errors are noise to the outer rule, which stops refining at four times their bound
/// (its noise floor) and may report up to about that much: with inner integrals at tol/4
/// the sum of the two estimates stays within `tol` (at tol/2 it reached 1.05·tol on the
/// `energy-albedo` preset).
/// Its integrals share one [`with_budget`] scope.
pub fn average_albedo(brdf: &Brdf, tol: f64) -> (f64, f64, u64) {
    with_budget(INTEGRAL_EVAL_BUDGET, || average_albedo_unbounded(brdf, tol))
}

fn average_albedo_unbounded(brdf: &Brdf, tol: f64) -> (f64, f64, u64) {
    let inner_err = std::cell::Cell::new(0.0f64);
    let evals = std::cell::Cell::new(0u64);
    let outer = integrate(
        |mu: f64| {
            let (v, e, n) = directional_albedo(brdf, mu, 0.25 * tol);
            inner_err.set(inner_err.get().max(e[0]));
            evals.set(evals.get() + n);
            [2.0 * v[0] * mu]
        },
        0.0,
        1.0,
        Tolerance {
            abs: 0.5 * tol,
            initial_panels: 2,
            max_depth: 30,
            noise_floor: 4.0 * 0.25 * tol,
            ..Default::default()
        },
    );
    (
        outer.value[0],
        outer.error[0] + inner_err.get(),
        evals.get(),
    )
}
