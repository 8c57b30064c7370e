//! The rough dielectric kinds (GGX interface, exact Fresnel of the fresnel axis' relative
//! index η, separable or height-correlated Smith masking; Walter et al. 2007; the integrands
//! are in [`crate::model::btdf`]), each texel by the nested rule over micro-normals of
//! [`crate::kernels::micro_normals`]:
//!
//! * `dielectric-btdf`: reflection and transmission albedo R, T over (cos θv; roughness; η);
//! * `dielectric-albedo`: their sum E = R + T (one channel, integrated as one).
//!
//! (`dielectric-albedo-avg` is in `dielectric_average.rs`.) Here too: what the kinds share —
//! their validation, the relative index of each slice, the view cosine of a texel, and the
//! fibre path: the texels of one
//! (μ, roughness) along the fresnel axis whose μ and breakpoints are the same (the η ≥ 1
//! slices) are integrated together as the channels of one rule.

use super::{TableKind, TableSpec, TexelResult};
use crate::kernels::micro_normals::{integrate_micro_normals, Rule};
pub use crate::kernels::micro_normals::{phi_breaks, transmitted_horizon, MAX_ETAS};
use crate::kernels::roughness_fibre::{roughness_fibre_with, ROUGHNESS_FIBRE};
use crate::lut::Quantity;
use crate::model::btdf::{
    albedo_integrands, integrands_many, BelowOne, MicroNormal, RoughDielectric, SmithForm,
};
use crate::model::fresnel::dielectric;
use crate::model::{Fresnel, FresnelQuantity, Masking, Ndf, NdfKind};
use crate::quadrature::cc1d::Estimator;
use crate::quadrature::Estimate;

/// The checks every dielectric kind shares (the generic axis checks are done): a GGX
/// interface with Smith masking, no other Fresnel term or lobe, a fresnel axis of η, views
/// above the horizon.
pub(crate) fn validate(spec: &TableSpec) -> Result<(), String> {
    let m = &spec.model;
    let kind = spec.kind.name();
    let ndf = m
        .ndf
        .ok_or_else(|| format!("model.ndf is required for a {kind} table"))?;
    if ndf != NdfKind::Ggx {
        return Err(format!(
            "model.ndf must be ggx for a {kind} table (Walter et al. 2007), got {:?}",
            ndf.name()
        ));
    }
    if SmithForm::of(m.masking).is_none() {
        return Err(format!(
            "model.masking must be smith-separable (Walter et al. 2007, eq. 23: G1(v) G1(l) on both sides) or \
             smith-height-correlated (1/(1 + Lambda(v) + Lambda(l)) on both sides, as Cycles) for a {kind} table, got {:?}",
            m.masking.name()
        ));
    }
    if m.diffuse_weight != 0.0 {
        return Err(format!(
            "model.diffuse must be 0 for a {kind} table (it describes the interface only)"
        ));
    }
    if m.fresnel != Fresnel::None {
        return Err(format!(
            "model.fresnel must be none for a {kind} table: the exact dielectric Fresnel of the fresnel axis' eta \
             is used, got {:?}",
            m.fresnel.name()
        ));
    }
    let fresnel = spec.axes.iter().find(|a| a.name == "fresnel");
    match fresnel.map(|a| a.quantity) {
        Some(Quantity::Fresnel(q)) if q.is_eta() => {}
        Some(Quantity::Fresnel(q)) => {
            return Err(format!(
                "axes.fresnel.quantity must give the relative index for a {kind} table (the refraction needs \
                 eta itself; accepted: {}), got {:?}",
                eta_quantities(),
                q.name()
            ))
        }
        _ => {
            return Err(format!(
                "axes.fresnel needs a Fresnel quantity giving eta (accepted: {})",
                eta_quantities()
            ))
        }
    }
    if spec.kind != TableKind::DielectricAlbedoAvg {
        // (a critical-angle axis puts its texels differently in every slice)
        let slices = if spec.axes[0].warp.is_coupled() {
            spec.axes[2].size
        } else {
            1
        };
        for z in 0..slices {
            for i in 0..spec.axes[0].size {
                let mu = view_cosine(spec, i, z);
                if mu <= 0.0 {
                    let slice = if slices > 1 {
                        format!(
                            " in fresnel slice {z} (eta {})",
                            crate::numfmt::num(eta_of_slice(spec, z))
                        )
                    } else {
                        String::new()
                    };
                    return Err(format!(
                        "axes.cos_theta_v: texel {i}{slice} is at cosine {}; a texel at cosine 0 is not allowed for a {kind} \
                         table (its integrals divide by n.v): use the centers convention, a range starting above 0, \
                         or a clamp",
                        crate::numfmt::num(mu)
                    ));
                }
            }
        }
    }
    Ok(())
}

/// The names of the relative-index Fresnel quantities, for error messages.
pub(crate) fn eta_quantities() -> String {
    FresnelQuantity::ALL
        .iter()
        .filter(|q| q.is_eta())
        .map(|q| q.name())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The relative index η of slice `z` (the fresnel axis' texel `z`; NaN if the table has no
/// η axis, which validation refuses).
pub fn eta_of_slice(spec: &TableSpec, z: usize) -> f64 {
    spec.axes
        .iter()
        .find(|a| a.name == "fresnel")
        .and_then(|a| a.fresnel_parameter(z))
        .unwrap_or(f64::NAN)
}

/// The view cosine n·v of texel `i` of the `cos_theta_v` axis in slice `z`: the same in
/// every slice, but for a critical-angle axis ([`crate::lut::Warp::CriticalAngle`], EEVEE's
/// `btdf_split_sum_ggx`), whose texels sit about the critical cosine √(1 − η²) of the
/// slice's relative index η.
pub fn view_cosine(spec: &TableSpec, i: usize, z: usize) -> f64 {
    let a = &spec.axes[0];
    if !a.warp.is_coupled() {
        return a.coord(i);
    }
    a.coord_at(i, crate::lut::critical_cosine(eta_of_slice(spec, z)))
}

/// The masking form of a validated dielectric spec.
pub(crate) fn smith_of(spec: &TableSpec) -> SmithForm {
    SmithForm::of(spec.model.masking).unwrap_or(SmithForm::Separable)
}

/// `[R, T]` at a view with n·v = `mu`, to absolute tolerance `tol` per channel (separable
/// Smith masking).
pub fn reflect_transmit(m: &RoughDielectric, mu: f64, tol: f64) -> Estimate<2> {
    reflect_transmit_with(m, SmithForm::Separable, mu, tol)
}

/// [`reflect_transmit`] with the masking form `smith`.
pub fn reflect_transmit_with(
    m: &RoughDielectric,
    smith: SmithForm,
    mu: f64,
    tol: f64,
) -> Estimate<2> {
    reflect_transmit_etas_with::<2>(&m.ndf, smith, &[m.eta], mu, tol)
}

/// `[R, T]` for several relative indices `etas` at once (at most [`MAX_ETAS`], and
/// `2·etas.len() ≤ N`): channels `2k`, `2k + 1` are R and T of `etas[k]` (those beyond
/// `2·etas.len()` are 0), each to absolute tolerance `tol` with its own error estimate. One
/// nested rule serves them all: its panel boundaries are the union of every index's kinks
/// (for η ≥ 1 they are the same for all: the reflected horizon and π/2), a panel is refined
/// until every channel meets its share, and every node computes what does not depend on η
/// once ([`integrands_many`]). `evals` counts the u nodes, once however many indices they
/// serve. Separable Smith masking.
pub fn reflect_transmit_etas<const N: usize>(
    ndf: &Ndf,
    etas: &[f64],
    mu: f64,
    tol: f64,
) -> Estimate<N> {
    reflect_transmit_etas_with::<N>(ndf, SmithForm::Separable, etas, mu, tol)
}

/// [`reflect_transmit_etas`] with the masking form `smith`.
pub fn reflect_transmit_etas_with<const N: usize>(
    ndf: &Ndf,
    smith: SmithForm,
    etas: &[f64],
    mu: f64,
    tol: f64,
) -> Estimate<N> {
    assert!(
        etas.len() <= MAX_ETAS && 2 * etas.len() <= N,
        "{} indices in {N} channels",
        etas.len()
    );
    let mu1 = mu.min(1.0);
    let g1v = ndf.g1(mu1);
    if let [eta] = *etas {
        if eta < 1.0 && mu1 > 0.0 {
            let below = BelowOne::new(eta, mu1, g1v);
            return integrate_micro_normals(ndf, Rule::standard(etas), mu, tol, |h| {
                let [r, t] = below.integrands(ndf, smith, h);
                let mut y = [0.0; N];
                (y[0], y[1]) = (r, t);
                y
            });
        }
    }
    integrate_micro_normals(ndf, Rule::standard(etas), mu, tol, |h: &MicroNormal| {
        integrands_many::<N>(ndf, smith, etas, mu1, g1v, h)
    })
}

/// The integrands of a dielectric kind for several indices at once, `K` channels per index
/// (at most [`FIBRE_CHANNELS`] in all): [`integrands_many`] or [`albedo_integrands`].
type Integrands = fn(&Ndf, SmithForm, &[f64], f64, f64, &MicroNormal) -> [f64; FIBRE_CHANNELS];

/// Channels of one shared rule of the new dielectric kinds' fibres.
const FIBRE_CHANNELS: usize = 8;

/// The channels per index and the integrands of a 3D dielectric kind other than
/// `dielectric-btdf` (whose fibre keeps its own grouping, [`reflect_transmit_fibre`]).
fn integrands_of(kind: TableKind) -> (usize, Integrands) {
    match kind {
        TableKind::DielectricBtdf => (2, integrands_many::<FIBRE_CHANNELS>),
        _ => (1, albedo_integrands::<FIBRE_CHANNELS>),
    }
}

/// The channels (`k` per index) of the indices `etas` at a view with n·v = `mu`, each to
/// absolute tolerance `tol`, by one shared rule (at most `FIBRE_CHANNELS / k` indices).
fn shared_rule(
    ndf: &Ndf,
    smith: SmithForm,
    (k, integrands): (usize, Integrands),
    etas: &[f64],
    mu: f64,
    tol: f64,
) -> Estimate<FIBRE_CHANNELS> {
    debug_assert!(k * etas.len() <= FIBRE_CHANNELS);
    let mu1 = mu.min(1.0);
    let g1v = ndf.g1(mu1);
    let rule = Rule {
        etas,
        cones: &[],
        view_peak: false,
        estimator: Estimator::Tail,
        alphas: &[],
    };
    if let [eta] = *etas {
        if eta < 1.0 && mu1 > 0.0 {
            // η < 1 with the standard estimate: on Cycles' glass_inv_E grid the tail estimate
            // fell below the error at 46 of 4,096 texels, by up to 4e-7 (grazing views with
            // height-correlated masking; the standard one at none, with the layer break of
            // `micro_normals`: examples/glass_probe.rs)
            let rule = Rule {
                estimator: Estimator::Standard,
                ..rule
            };
            let below = BelowOne::new(eta, mu1, g1v);
            return integrate_micro_normals(ndf, rule, mu, tol, |h| {
                let [r, t] = below.integrands(ndf, smith, h);
                let mut y = [0.0; FIBRE_CHANNELS];
                match k {
                    1 => y[0] = r + t,
                    _ => (y[0], y[1]) = (r, t),
                }
                y
            });
        }
    }
    integrate_micro_normals(ndf, rule, mu, tol, |h: &MicroNormal| {
        integrands(ndf, smith, etas, mu1, g1v, h)
    })
}

/// How the slices of one fibre (fixed roughness and view texel, every η) are grouped into
/// shared rules of up to `per_rule` slices: consecutive slices of η ≥ 1 with the same view
/// cosine `mus[z]` (their breakpoints are all the same) together; each η < 1 slice alone,
/// since its breakpoints (critical angle, transmitted horizon) depend on η and the union of
/// several slices' breakpoints costs more nodes than it shares (measured on the
/// `dielectric-btdf` preset, `examples/fibre_check.rs union`: its four η < 1 slices as one
/// rule 37,340 nodes per fibre against 29,707 for the four alone, and about twice the CPU
/// time, each node then serving 8 channels; BENCHMARKS.md, fib6). Returns slice indices per
/// group, in slice order.
pub fn fibre_groups_of(etas: &[f64], mus: &[f64], per_rule: usize) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut open: Option<usize> = None;
    for (z, &eta) in etas.iter().enumerate() {
        if eta < 1.0 {
            groups.push(vec![z]);
            open = None;
            continue;
        }
        match open {
            Some(g) if groups[g].len() < per_rule && mus[groups[g][0]] == mus[z] => {
                groups[g].push(z)
            }
            _ => {
                open = Some(groups.len());
                groups.push(vec![z]);
            }
        }
    }
    groups
}

/// Most indices per shared rule in a `dielectric-btdf` fibre (channels R, T each: 8
/// channels).
const FIBRE_ETAS: usize = 4;

/// [`fibre_groups_of`] of a `dielectric-btdf` fibre at one view cosine: groups of up to 4.
pub fn fibre_groups(etas: &[f64]) -> Vec<Vec<usize>> {
    fibre_groups_of(etas, &vec![0.0; etas.len()], FIBRE_ETAS)
}

/// `[R, T]` of every slice of one fibre: `etas` at one view `mu` and one NDF, grouped by
/// [`fibre_groups`]; per slice its values, its own error estimates and the evaluations of
/// its group (counted at the group's first slice, 0 at the others). Separable masking.
pub fn reflect_transmit_fibre(
    ndf: &Ndf,
    etas: &[f64],
    mu: f64,
    tol: f64,
) -> Vec<([f64; 2], [f64; 2], u64)> {
    let mus = vec![mu; etas.len()];
    reflect_transmit_fibre_with(ndf, SmithForm::Separable, etas, &mus, tol)
}

/// [`reflect_transmit_fibre`] with the masking form `smith` and each slice's view cosine
/// `mus[z]` (one per slice, all equal for now; slices share a rule only where theirs are
/// equal).
pub fn reflect_transmit_fibre_with(
    ndf: &Ndf,
    smith: SmithForm,
    etas: &[f64],
    mus: &[f64],
    tol: f64,
) -> Vec<([f64; 2], [f64; 2], u64)> {
    let mut out = vec![([0.0; 2], [0.0; 2], 0); etas.len()];
    for g in fibre_groups_of(etas, mus, FIBRE_ETAS) {
        let group: Vec<f64> = g.iter().map(|&z| etas[z]).collect();
        let mu = mus[g[0]];
        let (value, error, evals): (Vec<f64>, Vec<f64>, u64) = if group.len() == 1 {
            let e = reflect_transmit_etas_with::<2>(ndf, smith, &group, mu, tol);
            (e.value.to_vec(), e.error.to_vec(), e.evals)
        } else {
            let e = reflect_transmit_etas_with::<{ 2 * FIBRE_ETAS }>(ndf, smith, &group, mu, tol);
            (e.value.to_vec(), e.error.to_vec(), e.evals)
        };
        for (k, &z) in g.iter().enumerate() {
            out[z] = (
                [value[2 * k], value[2 * k + 1]],
                [error[2 * k], error[2 * k + 1]],
                if k == 0 { evals } else { 0 },
            );
        }
    }
    out
}

/// The texel results of every slice of one fibre of a dielectric kind other than
/// `dielectric-btdf`: slices grouped by [`fibre_groups_of`] into shared rules of
/// `FIBRE_CHANNELS / k` slices, evaluations counted at each group's first slice.
fn kind_fibre(
    ndf: &Ndf,
    smith: SmithForm,
    kind: TableKind,
    etas: &[f64],
    mus: &[f64],
    tol: f64,
) -> Vec<TexelResult> {
    let (k, integrands) = integrands_of(kind);
    let mut out = vec![TexelResult::exact(vec![0.0; k]); etas.len()];
    for g in fibre_groups_of(etas, mus, FIBRE_CHANNELS / k) {
        let group: Vec<f64> = g.iter().map(|&z| etas[z]).collect();
        let e = shared_rule(ndf, smith, (k, integrands), &group, mus[g[0]], tol);
        for (j, &z) in g.iter().enumerate() {
            out[z] = TexelResult {
                value: e.value[k * j..k * (j + 1)].to_vec(),
                error: e.error[k * j..k * (j + 1)].to_vec(),
                evals: if j == 0 { e.evals } else { 0 },
            };
        }
    }
    out
}

/// One NDF per roughness texel (axis 1) of a validated dielectric spec.
pub(crate) fn ndfs(spec: &TableSpec) -> Vec<Ndf> {
    let kind = spec.model.ndf.unwrap_or(NdfKind::Ggx);
    (0..spec.axes[1].size)
        .map(|j| Ndf::new(kind, spec.axes[1].alpha(j).expect("roughness axis")).expect("validated"))
        .collect()
}

/// Every slice's η and, per view texel, every slice's view cosine.
pub(crate) fn etas_and_mus(spec: &TableSpec) -> (Vec<f64>, Vec<Vec<f64>>) {
    let nz = spec.axes[2].size;
    let etas: Vec<f64> = (0..nz).map(|z| eta_of_slice(spec, z)).collect();
    let mus = (0..spec.axes[0].size)
        .map(|i| (0..nz).map(|z| view_cosine(spec, i, z)).collect())
        .collect();
    (etas, mus)
}

/// The texel function of the 3D dielectric kinds: one texel by its own rule (as `readback`'s
/// exact values and the texel-by-texel path take it).
pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let tol = spec.tolerance;
    let smith = smith_of(spec);
    let kind = spec.kind;
    let ndfs = ndfs(spec);
    let (etas, mus) = etas_and_mus(spec);
    Box::new(move |idx| {
        let (ndf, eta, mu) = (&ndfs[idx[1]], etas[idx[2]], mus[idx[0]][idx[2]]);
        if kind == TableKind::DielectricBtdf {
            let e = reflect_transmit_etas_with::<2>(ndf, smith, &[eta], mu, tol);
            return TexelResult {
                value: e.value.to_vec(),
                error: e.error.to_vec(),
                evals: e.evals,
            };
        }
        kind_fibre(ndf, smith, kind, &[eta], &[mu], tol)
            .pop()
            .expect("one texel")
    })
}

/// The fibre path of the 3D dielectric kinds ([`super::FibreFn`]): every η slice of one
/// (μ texel, roughness) pair, `dielectric-btdf` by [`reflect_transmit_fibre_with`], the
/// others by shared rules of up to 8 channels.
pub(crate) fn fibre_fn(spec: &TableSpec) -> super::FibreFn {
    let tol = spec.tolerance;
    let smith = smith_of(spec);
    let kind = spec.kind;
    let ndfs = ndfs(spec);
    let (etas, mus) = etas_and_mus(spec);
    // (the η < 1 slices go by roughness fibres: `roughness_fibres`)
    let above: Vec<usize> = (0..etas.len()).filter(|&z| etas[z] >= 1.0).collect();
    let per_texel = integrands_of(kind).0;
    Box::new(move |i, j| {
        let etas_above: Vec<f64> = above.iter().map(|&z| etas[z]).collect();
        let mus_above: Vec<f64> = above.iter().map(|&z| mus[i][z]).collect();
        let done: Vec<TexelResult> = if kind == TableKind::DielectricBtdf {
            reflect_transmit_fibre_with(&ndfs[j], smith, &etas_above, &mus_above, tol)
                .into_iter()
                .map(|(value, error, evals)| TexelResult {
                    value: value.to_vec(),
                    error: error.to_vec(),
                    evals,
                })
                .collect()
        } else {
            kind_fibre(&ndfs[j], smith, kind, &etas_above, &mus_above, tol)
        };
        let mut out = vec![TexelResult::exact(vec![0.0; per_texel]); etas.len()];
        for (&z, r) in above.iter().zip(done) {
            out[z] = r;
        }
        out
    })
}

/// The roughness-fibre path of the 3D dielectric kinds ([`super::RoughnessFibres`]): every
/// η < 1 slice's texels at one view texel by [`roughness_fibres_with`]: `dielectric-btdf`'s
/// R, T = F w_r, (1 − F) w_t (`BelowOne`), `dielectric-albedo`'s E = F w_r + (1 − F) w_t
/// (`albedo_integrands`).
pub(crate) fn roughness_fibres(spec: &TableSpec) -> super::RoughnessFibres {
    if spec.kind == TableKind::DielectricBtdf {
        roughness_fibres_with::<{ 2 * ROUGHNESS_FIBRE }, 2>(spec, |eta, c| {
            let f = dielectric(c, eta);
            [[f, 0.0], [0.0, 1.0 - f]]
        })
    } else {
        roughness_fibres_with::<ROUGHNESS_FIBRE, 1>(spec, |eta, c| {
            let f = dielectric(c, eta);
            [[f, 1.0 - f]]
        })
    }
}

/// A dielectric kind's roughness-fibre path: every η < 1 slice's texels at one view texel
/// by [`roughness_fibre_with`] (runs of up to [`ROUGHNESS_FIBRE`] roughnesses in order of α
/// per rule, evaluations counted at each run's first, narrowest roughness), `K` channels per
/// texel whose coefficients of w_r and w_t at relative index η and v·h = c are
/// `coef(η, c)`; `N` = `K`·[`ROUGHNESS_FIBRE`].
pub(crate) fn roughness_fibres_with<const N: usize, const K: usize>(
    spec: &TableSpec,
    coef: fn(f64, f64) -> [[f64; 2]; K],
) -> super::RoughnessFibres {
    let tol = spec.tolerance;
    let smith = smith_of(spec);
    let ndfs = ndfs(spec);
    let (etas, mus) = etas_and_mus(spec);
    super::RoughnessFibres {
        slices: etas.iter().map(|&eta| eta < 1.0).collect(),
        run: Box::new(move |i, z| {
            let eta = etas[z];
            roughness_fibre_with::<N, K>(&ndfs, smith, eta, mus[i][z], tol, |c| coef(eta, c))
                .into_iter()
                .map(|e| TexelResult {
                    value: e.value.to_vec(),
                    error: e.error.to_vec(),
                    evals: e.evals,
                })
                .collect()
        }),
    }
}

/// Whether a masking term is one the dielectric kinds take.
pub fn accepts_masking(m: Masking) -> bool {
    SmithForm::of(m).is_some()
}

fn ch(name: &str, meaning: &str) -> crate::lut::Channel {
    crate::lut::Channel {
        name: name.into(),
        meaning: meaning.into(),
    }
}

/// The channels of `dielectric-albedo` and `dielectric-albedo-avg`.
pub(crate) fn channels(spec: &TableSpec) -> Vec<crate::lut::Channel> {
    match spec.kind {
        TableKind::DielectricAlbedoAvg => vec![ch(
            "E_avg",
            "E_avg = 2 int_0^1 E(mu) mu dmu, E = R + T: the cosine-weighted average of the single-scattering albedo of the interface (1 - E_avg: the energy it loses to single scattering under uniform light)",
        )],
        _ => vec![ch(
            "E",
            "E = R + T = int f_r (n.l) dw_l + int f_t |n.l| dw_l: the fraction of light arriving at cos theta_v = mu that single scattering reflects or transmits (exact dielectric F, total internal reflection included; radiance not scaled by 1/eta^2)",
        )],
    }
}

/// How a shader uses the channels of the kinds of [`channels`].
pub(crate) fn reconstruction(spec: &TableSpec) -> &'static str {
    match spec.kind {
        TableKind::DielectricAlbedoAvg => "E_avg(roughness; eta): with E(mu) of a dielectric-albedo table, the multiple-scattering \
            compensation of a rough dielectric (Kulla-Conty style: f_ms proportional to (1 - E(mu_o))(1 - E(mu_i))/(1 - E_avg)); \
            Cycles scales its glass closures by 1/E.",
        _ => "E = R + T: the fraction of light arriving at cos theta_v = mu that a rough dielectric interface of relative index \
            eta reflects or transmits by single scattering; 1 - E is lost to it (Cycles scales its glass closures by 1/E). \
            For eta < 1 the view is inside the denser medium and E includes total internal reflection.",
    }
}
