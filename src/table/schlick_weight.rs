//! `schlick-weight-vndf` and `schlick-weight-albedo`: the generalized-Schlick blend weight
//! s(v·h) of F = F0 + (F90 − F0)·s averaged over (cos θv; roughness; exponent or η), 3D, in
//! two ways, one kind each:
//!
//! * `schlick-weight-vndf`, `S_vndf = ∫ s(v·h) D_v(h) [n·l_r > 0] dω_h`: the mean weight over
//!   the GGX distribution of visible normals D_v = G1(v) (v·h) D(h)/(n·v) (Heitz 2014),
//!   micro-normals whose mirror direction l_r leaves below the horizon counting 0. This is
//!   what Cycles tabulates (`ggx_gen_schlick_s`, `ggx_gen_schlick_ior_s`): its generator
//!   averages the per-sample ratio of its closure's two Fresnel channels, eval.x/eval.y =
//!   s(v·h), over VNDF samples (`cycles_precompute.cpp`), and a shader uses
//!   F̄ = mix(F0, F90, S_vndf). It is not an energy ratio: the masking of l_r is left out.
//! * `schlick-weight-albedo`, `S_albedo = ∫ s f cos dω_l / ∫ f cos dω_l` (f with F = 1 and the
//!   model's masking): the albedo-weighted mean, for which `E·mix(F0, F90, S_albedo)` is
//!   exactly the albedo with that Fresnel term, `∫ F f cos dω_l`.
//!
//! The two differ by the masking G(v, l_r)/G1(v) inside the average.
//!
//! The weight s is `(1 − v·h)^e` for an exponent axis (`schlick-exponent`,
//! `schlick-exponent-ratio`; [`generalized_schlick_weight`]) and the exact dielectric
//! Fresnel normalized to Schlick's form, `saturate((F(v·h; η) − F0)/(1 − F0))`, for an η
//! axis ([`normalized_dielectric_weight`]; Cycles' generalized Schlick Fresnel with a
//! negative exponent). Both integrals go through the nested rule over micro-normals
//! ([`crate::kernels::micro_normals`]); an exponent's (1 − v·h)^e is not analytic where
//! v·h = 1 (h = v), so the rule puts a panel boundary where v·h peaks along each azimuth
//! (`view_peak`); an η < 1 adds its critical-angle kinks. The texels of one (μ, roughness)
//! share rules: all exponents, or the η ≥ 1 slices, up to 8 (`S_vndf`) or 7 (`S_albedo`:
//! channel 0 the shared ∫ f cos, then each slice's numerator) at a time.

use super::{TableKind, TableSpec, TexelResult};
use crate::kernels::micro_normals::{integrate_micro_normals, Rule};
use crate::lut::{Channel, Quantity};
use crate::model::btdf::{Facet, MicroNormal, SmithForm};
use crate::model::fresnel::{
    generalized_schlick_weight, normalized_dielectric_kink, normalized_dielectric_weight,
};
use crate::model::{Fresnel, Ndf, NdfKind};
use crate::quadrature::cc1d::Estimator;

/// The parameters of one slice: a generalized Schlick exponent or a relative index.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Param {
    Exponent(f64),
    Eta(f64),
}

impl Param {
    #[inline]
    fn weight(self, c: f64) -> f64 {
        match self {
            Param::Exponent(e) => generalized_schlick_weight(c, e),
            Param::Eta(eta) => normalized_dielectric_weight(c, eta),
        }
    }
}

/// Which average a table holds: its kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Average {
    /// `S_vndf` (`schlick-weight-vndf`): one channel per slice.
    Vndf,
    /// `S_albedo` (`schlick-weight-albedo`): channel 0 the shared ∫ f cos, then one
    /// numerator per slice.
    Albedo,
}

impl Average {
    fn of(spec: &TableSpec) -> Average {
        if spec.kind == TableKind::SchlickWeightAlbedo {
            Average::Albedo
        } else {
            Average::Vndf
        }
    }

    /// Slices per shared rule.
    fn group(self) -> usize {
        match self {
            Average::Vndf => CHANNELS,
            Average::Albedo => CHANNELS - 1,
        }
    }
}

/// Channels of one shared rule.
const CHANNELS: usize = 8;

/// The checks of both kinds (the generic axis checks are done, views above the horizon
/// among them): GGX with Smith masking, no other Fresnel term or lobe, a fresnel axis of
/// exponents or of η.
pub(crate) fn validate(spec: &TableSpec) -> Result<(), String> {
    let m = &spec.model;
    let kind = spec.kind.name();
    match m.ndf {
        Some(NdfKind::Ggx) => {}
        other => {
            return Err(format!(
            "model.ndf must be ggx for a {kind} table (the visible normals are GGX's), got {:?}",
            other.map_or("none", |n| n.name())
        ))
        }
    }
    if SmithForm::of(m.masking).is_none() {
        return Err(format!(
            "model.masking must be smith-separable or smith-height-correlated for a {kind} table (G1 of the \
             visible normals, G of the reflected direction), got {:?}",
            m.masking.name()
        ));
    }
    if m.fresnel != Fresnel::None || m.diffuse_weight != 0.0 {
        return Err(format!(
            "model.fresnel must be none and model.diffuse 0 for a {kind} table (the weight s comes from \
             the fresnel axis)"
        ));
    }
    match spec.axes[2].quantity {
        Quantity::Fresnel(q) if !q.is_f0() => Ok(()),
        _ => Err(format!(
            "axes.fresnel.quantity must be a generalized Schlick exponent (schlick-exponent, \
             schlick-exponent-ratio) or a relative index ({}) for a {kind} table",
            super::dielectric::eta_quantities()
        )),
    }
}

fn ch(name: &str, meaning: &str) -> Channel {
    Channel {
        name: name.into(),
        meaning: meaning.into(),
    }
}

/// The one channel of each kind.
pub(crate) fn channels(spec: &TableSpec) -> Vec<Channel> {
    vec![match Average::of(spec) {
        Average::Vndf => ch(
            "S_vndf",
            "S_vndf = int s(v.h) D_v(h) [n.l_r > 0] dw_h: the mean blend weight over the GGX visible normals (D_v = G1(v) (v.h) D / (n.v)), micro-normals reflecting below the horizon counting 0 (Cycles' gen_schlick tables; not an albedo ratio); F = mix(F0, F90, S_vndf)",
        ),
        Average::Albedo => ch(
            "S_albedo",
            "S_albedo = int s f cos dw_l / int f cos dw_l (f with F = 1): the albedo-weighted mean blend weight; E mix(F0, F90, S_albedo) = int F f cos dw_l exactly",
        ),
    }]
}

pub(crate) fn reconstruction(spec: &TableSpec) -> &'static str {
    match Average::of(spec) {
        Average::Vndf => "The generalized Schlick Fresnel F(v.h) = F0 + (F90 - F0) s(v.h), s = (1 - v.h)^e (exponent axis) or the exact \
            dielectric Fresnel normalized to Schlick's form (eta axis). S_vndf is the mean of s over the GGX visible normals, as \
            Cycles uses it: F_avg = mix(F0, F90, S_vndf), multiplied into the albedo E of the same roughness (an approximation: \
            the masking of the reflected direction is not in the average).",
        Average::Albedo => "The generalized Schlick Fresnel F(v.h) = F0 + (F90 - F0) s(v.h), s = (1 - v.h)^e (exponent axis) or the \
            exact dielectric Fresnel normalized to Schlick's form (eta axis). S_albedo is the albedo-weighted mean: \
            E * mix(F0, F90, S_albedo) = int F f cos dw_l exactly, with E from an albedo table of the same masking.",
    }
}

/// Every slice's parameter.
fn params(spec: &TableSpec) -> Vec<Param> {
    let a = &spec.axes[2];
    (0..a.size)
        .map(|z| {
            let p = a.fresnel_parameter(z).unwrap_or(f64::NAN);
            match a.quantity {
                Quantity::Fresnel(q) if q.is_exponent() => Param::Exponent(p),
                _ => Param::Eta(p),
            }
        })
        .collect()
}

/// Groups of slices sharing one rule: consecutive exponents, or consecutive η ≥ 1, up to
/// `per_rule`; each η < 1 alone (its kinks are its own).
fn groups(ps: &[Param], per_rule: usize) -> Vec<Vec<usize>> {
    let below = |p: &Param| matches!(p, Param::Eta(e) if *e < 1.0);
    let mut out: Vec<Vec<usize>> = Vec::new();
    for (z, p) in ps.iter().enumerate() {
        match out.last_mut() {
            Some(g) if !below(p) && g.len() < per_rule && !below(&ps[g[0]]) => g.push(z),
            _ => out.push(vec![z]),
        }
    }
    out
}

/// The rule of one group at view `mu`: `S_vndf`, channel k the numerator of slice k;
/// `S_albedo`, channel 0 = ∫ f cos, channel k + 1 the numerator of slice k.
fn rule(
    ndf: &Ndf,
    smith: SmithForm,
    avg: Average,
    ps: &[Param],
    mu: f64,
    tol: f64,
) -> crate::quadrature::Estimate<CHANNELS> {
    let mu1 = mu.min(1.0);
    let g1v = ndf.g1(mu1);
    let etas: Vec<f64> = ps
        .iter()
        .filter_map(|p| match p {
            // (η ≥ 1 has no kinks of its own)
            Param::Eta(e) if *e < 1.0 => Some(*e),
            _ => None,
        })
        .collect();
    let peak = ps.iter().any(|p| matches!(p, Param::Exponent(_)));
    // the clamp's kink on the cone v·h = c* of each η above ≈ 3.7
    let cones: Vec<f64> = ps
        .iter()
        .filter_map(|p| match p {
            Param::Eta(e) => normalized_dielectric_kink(*e),
            Param::Exponent(_) => None,
        })
        .collect();
    let r = Rule {
        etas: &etas,
        cones: &cones,
        view_peak: peak,
        estimator: Estimator::Tail,
        alphas: &[],
    };
    integrate_micro_normals(ndf, r, mu, tol, |h: &MicroNormal| {
        let mut y = [0.0; CHANNELS];
        let Some(f) = Facet::new(ndf, smith, mu1, g1v, h) else {
            return y;
        };
        match avg {
            Average::Vndf => {
                // D_v [n.l_r > 0] = G1(v) w where the mirror direction leaves above the horizon
                if f.gr > 0.0 {
                    let vndf = g1v * f.w;
                    for (o, p) in y.iter_mut().zip(ps) {
                        *o = p.weight(f.c) * vndf;
                    }
                }
            }
            Average::Albedo => {
                let fcos = f.w * f.gr;
                y[0] = fcos;
                for (o, p) in y[1..].iter_mut().zip(ps) {
                    *o = p.weight(f.c) * fcos;
                }
            }
        }
        y
    })
}

/// The texel results of the slices `ps` of one fibre (one view, one roughness).
fn fibre(
    ndf: &Ndf,
    smith: SmithForm,
    avg: Average,
    ps: &[Param],
    mu: f64,
    tol: f64,
) -> Vec<TexelResult> {
    let mut out = vec![TexelResult::exact(vec![0.0]); ps.len()];
    for g in groups(ps, avg.group()) {
        let group: Vec<Param> = g.iter().map(|&z| ps[z]).collect();
        if avg == Average::Vndf {
            let e = rule(ndf, smith, avg, &group, mu, tol);
            for (k, &z) in g.iter().enumerate() {
                out[z] = TexelResult {
                    value: vec![e.value[k]],
                    error: vec![e.error[k]],
                    evals: if k == 0 { e.evals } else { 0 },
                };
            }
            continue;
        }
        // S_albedo = num/den: its error is (δnum + S δden)/den ≤ 2δ/den (S ≤ 1); the rule
        // is run at tol/2 and again at tol·den/2 where den < 1 left that above tol
        let worst = |e: &crate::quadrature::Estimate<CHANNELS>| -> f64 {
            let den = e.value[0].max(f64::MIN_POSITIVE);
            (0..group.len())
                .map(|k| (e.error[k + 1] + e.error[0]) / den)
                .fold(0.0, f64::max)
        };
        let mut e = rule(ndf, smith, avg, &group, mu, 0.5 * tol);
        let mut evals = e.evals;
        if worst(&e) > tol && e.value[0] > 0.0 {
            let again = rule(ndf, smith, avg, &group, mu, 0.5 * tol * e.value[0].min(1.0));
            evals += again.evals;
            e = again;
        }
        let den = e.value[0];
        for (k, &z) in g.iter().enumerate() {
            let (num, en) = (e.value[k + 1], e.error[k + 1]);
            let (sa, ea) = if den > 0.0 {
                let sa = num / den;
                (sa, (en + sa.abs() * e.error[0]) / den)
            } else {
                (0.0, 0.0)
            };
            out[z] = TexelResult {
                value: vec![sa],
                error: vec![ea],
                evals: if k == 0 { evals } else { 0 },
            };
        }
    }
    out
}

fn setup(spec: &TableSpec) -> (Vec<Ndf>, Vec<Param>, SmithForm, Average) {
    let ndfs = (0..spec.axes[1].size)
        .map(|j| {
            Ndf::new(NdfKind::Ggx, spec.axes[1].alpha(j).expect("roughness axis"))
                .expect("validated")
        })
        .collect();
    (
        ndfs,
        params(spec),
        SmithForm::of(spec.model.masking).unwrap_or(SmithForm::Separable),
        Average::of(spec),
    )
}

/// One texel alone (`readback`'s exact values).
pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let (ndfs, ps, smith, avg) = setup(spec);
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    Box::new(move |idx| {
        fibre(
            &ndfs[idx[1]],
            smith,
            avg,
            &[ps[idx[2]]],
            axes[0].coord(idx[0]),
            tol,
        )
        .pop()
        .expect("one texel")
    })
}

/// The fibre path: every slice of one (μ, roughness).
pub(crate) fn fibre_fn(spec: &TableSpec) -> super::FibreFn {
    let (ndfs, ps, smith, avg) = setup(spec);
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    Box::new(move |i, j| fibre(&ndfs[j], smith, avg, &ps, axes[0].coord(i), tol))
}

/// The smooth limit α = 0: h = n, the reflection is the mirror (above the horizon for
/// μ > 0), so both averages are s(μ).
pub(crate) fn smooth_texel(spec: &TableSpec, idx: [usize; 3]) -> TexelResult {
    let s = params(spec)[idx[2]].weight(spec.axes[0].coord(idx[0]));
    TexelResult::exact(vec![s])
}
