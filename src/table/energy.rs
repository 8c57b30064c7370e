//! `kulla-conty` and `albedo-fresnel`: energy-compensation and Fresnel-resolved albedo
//! tables, built on the directional and average albedo of `albedo.rs`; validation,
//! channels and the shader recipe of these kinds and of `dielectric-btdf` (`dielectric.rs`).
//!
//! * `kulla-conty`: channels E(μ; r) and E_avg(r) at F = 1 in one 2D texture (E_avg repeated
//!   along μ), the inputs of Kulla & Conty's multiple-scattering lobe (see
//!   [`crate::model::energy`]).
//! * `albedo-fresnel`: E(μ; r; p) = ∫ f (n·l) dω_l with the Fresnel term given by the third
//!   axis: Schlick with F0 = p (`f0`, `sqrt-f0` axes), exact dielectric with η = p (`eta`,
//!   `eta-reflectance`), or exact conductor with η = p and the model's k.

use super::albedo::{average_albedo, directional_albedo};
use super::{TableKind, TableSpec, TexelResult};
use crate::lut::{Channel, Quantity};
use crate::model::{Brdf, Fresnel, FresnelQuantity, Masking, NdfKind};
use rayon::prelude::*;

/// The kind-specific checks of the three kinds (the generic axis checks are done;
/// `dielectric-btdf` is checked by [`super::dielectric::validate`]).
pub(crate) fn validate(spec: &TableSpec) -> Result<(), String> {
    let m = &spec.model;
    let kind = spec.kind.name();
    let ndf = m
        .ndf
        .ok_or_else(|| format!("model.ndf is required for a {kind} table"))?;
    if m.diffuse_weight != 0.0 {
        return Err(format!(
            "model.diffuse must be 0 for a {kind} table (it describes the specular lobe only)"
        ));
    }
    if ndf == NdfKind::Charlie && m.masking.is_smith() {
        return Err(
            "smith masking of the charlie NDF is not supported: use masking ashikhmin".into(),
        );
    }
    let fq = match spec.axes.get(2).map(|a| a.quantity) {
        Some(Quantity::Fresnel(q)) => Some(q),
        Some(_) => {
            return Err(format!(
                "axes.fresnel needs a Fresnel quantity (accepted: {})",
                FresnelQuantity::ALL.map(|q| q.name()).join(", ")
            ))
        }
        None => None,
    };
    match spec.kind {
        TableKind::KullaConty => {
            if m.fresnel != Fresnel::None {
                return Err(format!(
                    "model.fresnel must be none for a kulla-conty table: E and E_avg are taken at F = 1 and the \
                     Fresnel term enters through F_avg (see the sidecar's reconstruction), got {:?}",
                    m.fresnel.name()
                ));
            }
        }
        TableKind::AlbedoFresnel => {
            let q = fq.expect("three axes checked");
            if q.is_exponent() {
                return Err(format!(
                    "axes.fresnel.quantity {:?} (a generalized Schlick exponent) applies to schlick-weight tables only; \
                     an albedo-fresnel axis gives F0 (f0, sqrt-f0) or eta (eta, eta-reflectance, inverse-eta-reflectance)",
                    q.name()
                ));
            }
            match (q.is_f0(), m.fresnel) {
                (false, Fresnel::None) if spec.axes[2].fresnel_parameter(0).unwrap_or(1.0) < 1.0 => {
                    return Err(format!(
                        "axes.fresnel: the exact dielectric albedo-fresnel table needs eta >= 1 (the view outside the \
                         denser medium), got eta = {} at texel 0; for eta < 1 total internal reflection puts a kink \
                         inside the reflection integral: use a dielectric-btdf table, which integrates across it",
                        spec.axes[2].fresnel_parameter(0).unwrap_or(f64::NAN)
                    ))
                }
                (_, Fresnel::None) => {}
                (false, Fresnel::Conductor { .. }) => {}
                _ => {
                    return Err(format!(
                        "model.fresnel must be none for an albedo-fresnel table (the fresnel axis gives {}), or \
                         conductor with an eta or eta-reflectance axis (the axis gives eta, the model k); got {:?} \
                         with a {} axis",
                        if q.is_f0() { "Schlick's F0" } else { "the exact dielectric eta" },
                        m.fresnel.name(),
                        q.name()
                    ))
                }
            }
        }
        TableKind::DielectricBtdf => super::dielectric::validate(spec)?,
        _ => unreachable!("not an energy kind"),
    }
    Ok(())
}

/// The Fresnel term of slice `z` of an `albedo-fresnel` or `dielectric-btdf` table.
pub fn fresnel_of_slice(spec: &TableSpec, z: usize) -> Fresnel {
    let ax = &spec.axes[2];
    let p = ax.fresnel_parameter(z).expect("a fresnel axis");
    match ax.quantity {
        Quantity::Fresnel(q) if q.is_f0() => Fresnel::Schlick { f0: p },
        _ => match spec.model.fresnel {
            Fresnel::Conductor { k, .. } => Fresnel::Conductor { eta: p, k },
            _ => Fresnel::Dielectric { eta: p },
        },
    }
}

fn ch(name: &str, meaning: &str) -> Channel {
    Channel {
        name: name.into(),
        meaning: meaning.into(),
    }
}

pub(crate) fn channels(spec: &TableSpec) -> Vec<Channel> {
    match spec.kind {
        TableKind::KullaConty => vec![
            ch("E", "E(mu; roughness) = int f (n.l) dw_l with F = 1: the single-scattering directional albedo"),
            ch("E_avg", "E_avg(roughness) = 2 int_0^1 E(mu) mu dmu with F = 1 (the same value in every texel of a row)"),
        ],
        TableKind::AlbedoFresnel => vec![ch(
            "E",
            "E(mu; roughness; p) = int f (n.l) dw_l with the Fresnel term of the fresnel axis' parameter p (Schlick F0, or exact eta)",
        )],
        TableKind::DielectricBtdf => vec![
            ch("R", "R = int f_r (n.l) dw_l over the upper hemisphere: reflected fraction (exact dielectric F, total internal reflection included)"),
            ch("T", "T = int f_t |n.l| dw_l over the lower hemisphere: transmitted fraction (radiance not scaled by 1/eta^2)"),
        ],
        _ => unreachable!("not an energy kind"),
    }
}

/// How a shader uses the channels.
pub(crate) fn reconstruction(spec: &TableSpec) -> &'static str {
    match spec.kind {
        TableKind::KullaConty => "Kulla-Conty 2017: e_o = E(mu_o; r) and e_i = E(mu_i; r) (channel E, two lookups at the same roughness), \
            e_avg = E_avg (channel E_avg, any mu); f_ms(mu_o, mu_i) = (1 - e_o)(1 - e_i) / (pi (1 - e_avg)); with a Fresnel term multiply f_ms by \
            F_avg^2 e_avg / (1 - F_avg (1 - e_avg)), F_avg = 2 int_0^1 F(mu) mu dmu ((20 F0 + 1)/21 for Schlick, per colour channel); shade with f + f_ms. \
            Under uniform (image-based) lighting f_ms integrates to (1 - e_o) times that factor.",
        TableKind::AlbedoFresnel => "E(mu; roughness; p): the directional albedo with the Fresnel term resolved, not factored as in the split sum. \
            Sample at the fresnel axis coordinate of the material's F0 or eta (axes[2].parameter_mapping) and use it where a split-sum \
            E = F0 A + B would be used; 1 - E is the energy that single scattering does not reflect with that Fresnel term.",
        TableKind::DielectricBtdf => "R = reflected and T = transmitted fraction of light arriving at cos theta_v = mu on a rough dielectric \
            interface of relative index eta (the fresnel axis); 1 - R - T is the energy lost to single scattering; \
            R + T <= 1. For eta < 1 the view is inside the denser medium and R includes total internal reflection.",
        _ => unreachable!("not an energy kind"),
    }
}

pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    match spec.kind {
        TableKind::KullaConty => {
            let brdfs = super::texel::brdfs_per_roughness(spec);
            // E_avg of every row first (each a pure function of its α: deterministic)
            let avg: Vec<(f64, f64, u64)> =
                brdfs.par_iter().map(|b| average_albedo(b, tol)).collect();
            Box::new(move |idx| {
                let (v, e, n) = directional_albedo(&brdfs[idx[1]], axes[0].coord(idx[0]), tol);
                let (av, ae, an) = avg[idx[1]];
                TexelResult {
                    value: vec![v[0], av],
                    error: vec![e[0], ae],
                    // the row's E_avg cost is counted once, at its first texel
                    evals: n + if idx[0] == 0 { an } else { 0 },
                }
            })
        }
        TableKind::AlbedoFresnel => {
            let ny = axes[1].size;
            let brdfs: Vec<Brdf> = (0..ny * axes[2].size)
                .into_par_iter()
                .map(|k| {
                    let mut m = spec.model.clone();
                    m.fresnel = fresnel_of_slice(spec, k / ny);
                    let b = m
                        .brdf(axes[1].alpha(k % ny).expect("roughness axis"))
                        .expect("validated");
                    if let Some(s) = &b.specular {
                        s.prepare();
                    }
                    b
                })
                .collect();
            Box::new(move |idx| {
                let (v, e, n) =
                    directional_albedo(&brdfs[idx[2] * ny + idx[1]], axes[0].coord(idx[0]), tol);
                TexelResult {
                    value: v.to_vec(),
                    error: e.to_vec(),
                    evals: n,
                }
            })
        }
        TableKind::DielectricBtdf => super::dielectric::texel_fn(spec),
        _ => unreachable!("not an energy kind"),
    }
}

/// The fibre path ([`super::FibreFn`]) of a table kind, where it has one: `dielectric-btdf`
/// ([`super::dielectric::fibre_fn`]) and `albedo-fresnel` with the exact dielectric or
/// conductor Fresnel term of a smooth lobe peaked at the normal ([`fresnel_fibre_fn`]).
/// `None`: the table is baked texel by texel.
pub(crate) fn fibre_fn(spec: &TableSpec) -> Option<super::FibreFn> {
    match spec.kind {
        TableKind::DielectricBtdf | TableKind::DielectricAlbedo => {
            Some(super::dielectric::fibre_fn(spec))
        }
        TableKind::SchlickWeightVndf | TableKind::SchlickWeightAlbedo => {
            Some(super::schlick_weight::fibre_fn(spec))
        }
        TableKind::DielectricSchlick => Some(super::dielectric_schlick::fibre_fn(spec)),
        TableKind::AlbedoFresnel => fresnel_fibre_fn(spec),
        _ => None,
    }
}

/// The roughness-fibre path ([`super::RoughnessFibres`]) of a table kind with a fibre path,
/// where it has one: the η < 1 slices of the 3D dielectric kinds.
pub(crate) fn roughness_fibres(spec: &TableSpec) -> Option<super::RoughnessFibres> {
    match spec.kind {
        TableKind::DielectricSchlick => Some(super::dielectric_schlick::roughness_fibres(spec)),
        TableKind::DielectricBtdf | TableKind::DielectricAlbedo => {
            Some(super::dielectric::roughness_fibres(spec))
        }
        _ => None,
    }
}

/// Slices integrated together by one rule of [`fresnel_fibre_fn`] (its channel count).
const FRESNEL_FIBRE_SLICES: usize = 8;

/// E(μ) of one BRDF for several Fresnel terms at once: the directional albedo of `brdf`
/// (whose own Fresnel term is ignored) with each of `fresnels` in turn, to absolute tolerance
/// `tol` each. E_p(μ) = ∫ D G F_p(v·h)/(4 n·v) dω_l differs between the terms only in the
/// factor F_p(v·h), so up to `FRESNEL_FIBRE_SLICES` of them are the channels of one tensor
/// rule ([`integrate_over_l_cc_counted`](crate::hemisphere::tensor::integrate_over_l_cc_counted)):
/// the nodes, D·G and the Jacobians are computed once and multiplied by each term's F. The
/// rule refines until every channel's own estimate meets `tol`, and each term keeps its own
/// channel's estimate; evaluations count nodes once (returned with the group's first term,
/// 0 with the others). Where the shared rule does not converge, the group's terms go one by
/// one through [`directional_albedo`], the abandoned attempt counted too; so do all terms of
/// a BRDF outside the shared path's scope (a Charlie lobe, V-groove masking, a diffuse lobe:
/// `uses_fresnel_fibre` keeps such tables texel by texel). Returns `[value], [error],
/// evaluations` per term.
pub fn directional_albedo_fresnels(
    brdf: &Brdf,
    fresnels: &[Fresnel],
    mu: f64,
    tol: f64,
) -> Vec<([f64; 1], [f64; 1], u64)> {
    use crate::hemisphere::tensor::{integrate_over_l_cc_counted, InnerWarp};
    let s = brdf.specular.as_ref().expect("a specular lobe");
    let warp = InnerWarp::for_ndf(&s.ndf);
    // (a lobe outside this path's scope: every term by the per-term path, no attempt)
    let shared = matches!(warp, InnerWarp::TanOverScale(_))
        && s.masking != Masking::VGroove
        && brdf.diffuse_weight == 0.0;
    let mut out = Vec::with_capacity(fresnels.len());
    for fs in fresnels.chunks(FRESNEL_FIBRE_SLICES) {
        let shared_rule = |n: &crate::hemisphere::Node| {
            let cw = s.cosine_weighted_with(n, 1.0);
            let mut y = [0.0; FRESNEL_FIBRE_SLICES];
            for (k, f) in fs.iter().enumerate() {
                y[k] = cw * f.eval(n.v_dot_h);
            }
            y
        };
        let e = if shared {
            integrate_over_l_cc_counted::<FRESNEL_FIBRE_SLICES, _>(mu, warp, tol, shared_rule)
        } else {
            Err(0)
        };
        match e {
            Ok(e) => out.extend(
                (0..fs.len())
                    .map(|k| ([e.value[k]], [e.error[k]], if k == 0 { e.evals } else { 0 })),
            ),
            Err(spent) => {
                for (k, &f) in fs.iter().enumerate() {
                    let mut b = brdf.clone();
                    if let Some(s) = b.specular.as_mut() {
                        s.fresnel = f;
                    }
                    let (v, e, n) = directional_albedo(&b, mu, tol);
                    out.push((v, e, n + if k == 0 { spent } else { 0 }));
                }
            }
        }
    }
    out
}

/// The fibre path of an `albedo-fresnel` table with an exact Fresnel axis
/// ([`uses_fresnel_fibre`]): every slice of one (μ, roughness) by
/// [`directional_albedo_fresnels`].
fn fresnel_fibre_fn(spec: &TableSpec) -> Option<super::FibreFn> {
    if !super::methods::uses_fresnel_fibre(spec) {
        return None;
    }
    let axes = spec.axes.clone();
    // one BRDF per roughness (axis 1), any numeric G1 built now (each a pure function of α)
    let brdfs: Vec<Brdf> = (0..axes[1].size)
        .into_par_iter()
        .map(|j| {
            let b = spec
                .model
                .brdf(axes[1].alpha(j).expect("roughness axis"))
                .expect("validated");
            if let Some(s) = &b.specular {
                s.prepare();
            }
            b
        })
        .collect();
    let tol = spec.tolerance;
    let fresnels: Vec<Fresnel> = (0..axes[2].size)
        .map(|z| fresnel_of_slice(spec, z))
        .collect();
    Some(Box::new(move |i, j| {
        directional_albedo_fresnels(&brdfs[j], &fresnels, axes[0].coord(i), tol)
            .into_iter()
            .map(|(v, e, n)| TexelResult {
                value: v.to_vec(),
                error: e.to_vec(),
                evals: n,
            })
            .collect()
    }))
}
