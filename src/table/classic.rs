//! `classic-albedo` and `classic-albedo-aniso`: directional albedo tables of the classic
//! analytic models of [`crate::model::classic`] (Phong, modified Phong, Blinn-Phong
//! (s+8)/8π, Ward with its three normalizations, Ashikhmin–Shirley, Lafortune).
//!
//! * **Which albedo.** The table holds the view-side albedo
//!   `E(v) = ∫ f(l, v) (n·l) dω_l` — the radiance reflected towards a view at cos θv = μ
//!   under uniform white light, what a renderer samples (for energy compensation or ambient
//!   light). For a reciprocal model it equals the energy law's
//!   `E(ωi) = ∫ f(ωi, ωo) cos θo dωo` measured by `brdfbake laws`; for the original Phong
//!   model (not reciprocal, f = k_s (r·ωo)ⁿ / cos θi) the two differ: the view-side albedo
//!   is `k_s ∫ (r_l·v)ⁿ dω_l`, which is bounded (2π k_s/(n+1) at normal view).
//! * **Parameter axis** (`roughness`): the model's own parameter, stated in the sidecar:
//!   quantity `exponent` for the lobe exponent of Phong (n), modified Phong (n),
//!   Blinn-Phong (s), Ashikhmin–Shirley (n = n_u = n_v before anisotropy) and Lafortune
//!   (the lobe's n); quantity `alpha` for Ward's α (α_x = α_y = α before anisotropy).
//! * **Anisotropy axis** (`anisotropy`, 3D kind, Ward and Ashikhmin–Shirley only): a ∈ [0, 1]
//!   with aspect = √(1 − 0.9 a) (the parametrization of Burley 2012, "Physically-Based
//!   Shading at Disney", addenda: anisotropic GTR2/GGX), α_x = α/aspect, α_y = α·aspect for
//!   Ward; for Ashikhmin–Shirley the exponents n_u = n·aspect², n_v = n/aspect² (the same
//!   widening along the tangent x: a cosⁿ lobe has the Beckmann-equivalent width
//!   α² ≈ 2/(n+2), Walter et al. 2007 §5.2). The geometric mean (α_x α_y = α², n_u n_v = n²)
//!   stays the axis' parameter; a = 0 is exactly the isotropic model.
//! * **Azimuth** (3D kind): three channels, `E_avg` = (1/2π)∫E(μ, φv)dφv averaged over the
//!   view azimuth φv measured from the tangent x, `E_x` at φv = 0 (view in the x–n plane)
//!   and `E_y` at φv = 90° (view in the y–n plane). These models depend on the tangent
//!   components only through squares or products ωi,x ωo,x and ωi,y ωo,y, so
//!   E(φ) = E(−φ) = E(π − φ): the average is taken over [0, π/2].
//! * **Fast path**: `phong`, `modified-phong`, `blinn-phong` and `ward-gmd` (isotropic)
//!   are first integrated by [`crate::kernels::classic_lobes`] (azimuth in closed form,
//!   one 1D nested Clenshaw–Curtis integral per piece; [`fast_albedo`]); a texel whose
//!   estimate does not reach the tolerance, and every other model, as follows.
//! * **Quadrature**: the energy-law integrator of [`crate::laws`] (nested adaptive
//!   Gauss–Kronrod G7/K15 over the half vector, exact horizon, asinh lobe warp), applied to
//!   the model with its arguments swapped so that the view is the fixed direction; the
//!   azimuth average by adaptive Gauss–Kronrod over φv. Error estimates are summed as
//!   there and written to the sidecar.

use super::{TableKind, TableSpec, TexelResult};
use crate::laws::{directional_albedo, Albedo};
use crate::lut::{Axis, Channel};
use crate::model::classic::{Dir, Reflectance};
use crate::model::{Fresnel, Masking, RoughnessQuantity};
use serde_json::{json, Value};
use std::f64::consts::FRAC_PI_2;

/// The anisotropy parametrization, as the sidecar and `inspect` state it.
pub const ANISOTROPY_MAPPING: &str = "aspect = sqrt(1 - 0.9 a), a in [0, 1] (Burley 2012); ward: alpha_x = alpha/aspect, \
     alpha_y = alpha*aspect; ashikhmin-shirley: n_u = n*aspect^2, n_v = n/aspect^2; a = 0 is isotropic";

/// How the 3D kind handles the view azimuth, as the sidecar states it.
pub const AZIMUTH_HANDLING: &str = "three channels: E_avg = (1/2pi) int E(mu, phi_v) dphi_v averaged over the view azimuth phi_v \
     (measured from the tangent x, the direction of alpha_x / n_u; by the symmetry E(phi) = E(-phi) = E(pi - phi) of these models \
     the average is taken over [0, pi/2] by adaptive Gauss-Kronrod), E_x at phi_v = 0 (view in the x-n plane), E_y at phi_v = 90 \
     degrees (view in the y-n plane)";

pub use super::classic_model::{
    aspect, ClassicModel, EXPONENT_RANGE, TYPE_NAMES, WARD_ALPHA_RANGE,
};

/// A model seen from the view: `eval(v, l) = f(l, v)`, so that the energy-law integrator
/// (which fixes its first argument and integrates the second) gives the view-side albedo.
struct ViewFixed(Box<dyn Reflectance>);

impl Reflectance for ViewFixed {
    fn eval(&self, v: Dir, l: Dir) -> f64 {
        self.0.eval(l, v)
    }
    fn label(&self) -> String {
        self.0.label()
    }
    fn formula(&self) -> String {
        self.0.formula()
    }
    fn source(&self) -> &'static str {
        self.0.source()
    }
    fn isotropic(&self) -> bool {
        self.0.isotropic()
    }
    fn lobe_width(&self) -> f64 {
        self.0.lobe_width()
    }
    fn tolerance_floor(&self) -> f64 {
        self.0.tolerance_floor()
    }
}

/// The view-side directional albedo `∫ f(l, v)(n·l) dω_l` of `m` for a view at cos θv = `mu`
/// and azimuth `phi_v` from the tangent, to absolute tolerance `tol` (estimated).
pub fn view_albedo(m: Box<dyn Reflectance>, mu: f64, phi_v: f64, tol: f64) -> Albedo {
    directional_albedo(&ViewFixed(m), mu.clamp(0.0, 1.0).acos(), phi_v, tol)
}

/// The checks of the `roughness` axis of a classic table (called from the generic axis
/// checks with the axis' field name `f`).
pub(crate) fn check_parameter_axis(
    c: &ClassicModel,
    q: RoughnessQuantity,
    ax: &Axis,
    f: &str,
) -> Result<(), String> {
    let want = c.parameter_quantity();
    if q != want {
        return Err(format!(
            "{f}.quantity must be {:?} for a {} model ({}), got {:?}",
            want.name(),
            c.name(),
            c.parameter_meaning(),
            q.name()
        ));
    }
    let [lo, hi] = c.parameter_range();
    for i in 0..ax.size {
        let x = ax.coord(i);
        if !(lo..=hi).contains(&x) {
            return Err(format!(
                "{f}: texel {i} is at {x}, outside the accepted [{lo}, {hi}] (the axis is {} of the {} model)",
                c.parameter_meaning(),
                c.name()
            ));
        }
    }
    Ok(())
}

/// The kind-specific checks of the two classic kinds (the generic axis checks are done).
pub(crate) fn validate(spec: &TableSpec) -> Result<(), String> {
    let kind = spec.kind.name();
    let m = &spec.model;
    let c = m.classic.as_ref().ok_or_else(|| {
        format!(
            "model.classic is required for a {kind} table: an object with \"type\" (accepted: {TYPE_NAMES}) and its weights"
        )
    })?;
    if let Some(n) = m.ndf {
        return Err(format!(
            "model.ndf must be omitted for a {kind} table (model.classic is the model), got {:?}",
            n.name()
        ));
    }
    if m.masking != Masking::None {
        return Err(format!(
            "model.masking must be omitted for a {kind} table (classic models have no masking term), got {:?}",
            m.masking.name()
        ));
    }
    if m.fresnel != Fresnel::None {
        return Err(format!(
            "model.fresnel must be omitted for a {kind} table (ashikhmin-shirley's rs is its Schlick F0), got {:?}",
            m.fresnel.name()
        ));
    }
    if m.diffuse_weight != 0.0 {
        return Err(format!(
            "model.diffuse must be omitted for a {kind} table (the classic model's kd, rho_d or rd is its diffuse lobe)"
        ));
    }
    c.validate()?;
    if spec.kind == TableKind::ClassicAlbedoAniso && !c.anisotropic() {
        return Err(format!(
            "a classic-albedo-aniso table needs an anisotropic model (ward, ward-duer, ward-gmd or ashikhmin-shirley), \
             got {:?}; use a classic-albedo table",
            c.name()
        ));
    }
    if let ClassicModel::Lafortune { cx, cy, .. } = *c {
        if cx != cy {
            return Err(format!(
                "model.classic: cx ({cx}) and cy ({cy}) must be equal for a {kind} table: a lobe with cx != cy is \
                 anisotropic about a tangent the table has no axis for"
            ));
        }
    }
    if spec.dfg_layout.is_some() || spec.cloth {
        return Err(format!(
            "layout and cloth apply to dfg tables only, not {kind}"
        ));
    }
    if spec.cloth_alpha_min.is_some() {
        return Err(format!(
            "cloth_alpha_min applies to dfg tables with cloth only, not {kind}"
        ));
    }
    Ok(())
}

fn ch(name: &str, meaning: &str) -> Channel {
    Channel {
        name: name.into(),
        meaning: meaning.into(),
    }
}

const VIEW_ALBEDO: &str =
    "int f(l, v) (n.l) dw_l over the light hemisphere, view v at cos theta_v = mu fixed";

pub(crate) fn channels(spec: &TableSpec) -> Vec<Channel> {
    match spec.kind {
        TableKind::ClassicAlbedo => vec![ch("E", &format!("E(mu) = {VIEW_ALBEDO}"))],
        _ => vec![
            ch(
                "E_avg",
                &format!("E(mu) = {VIEW_ALBEDO}, averaged over the view azimuth: (1/2pi) int E dphi_v"),
            ),
            ch(
                "E_x",
                &format!("E(mu) = {VIEW_ALBEDO}, view azimuth phi_v = 0 (view in the tangent x - normal plane)"),
            ),
            ch(
                "E_y",
                &format!("E(mu) = {VIEW_ALBEDO}, view azimuth phi_v = 90 degrees (view in the bitangent y - normal plane)"),
            ),
        ],
    }
}

/// How a shader uses the channels.
pub(crate) fn reconstruction(spec: &TableSpec) -> &'static str {
    match spec.kind {
        TableKind::ClassicAlbedo => "E(mu): the fraction of uniform white light the classic model reflects towards a view at cos theta_v = mu \
            (the view-side albedo, equal to the energy law's albedo for reciprocal models); 1 - E is what it absorbs, E > 1 means the \
            model creates energy there (see brdfbake laws).",
        _ => "E_avg(mu; p; a) for an isotropic environment and unknown tangent orientation; E_x and E_y for a view in the tangent's or \
            bitangent's plane; for another view azimuth phi_v interpolate E_x cos^2 phi_v + E_y sin^2 phi_v as an approximation \
            (exact at 0 and 90 degrees only).",
    }
}

/// The quadrature method, as the sidecar states it.
pub const METHOD: &str = "the energy-law integrator (brdfbake laws) with the view fixed: nested adaptive Gauss-Kronrod (G7/K15) over the \
    half vector of the view, phi in [0, 2 pi], theta_h up to the exact horizon pi/4 + psi/2 (tan psi = tan theta_v cos phi) with the \
    lobe warp u = asinh(tan theta_h / w), w the model's lobe width; error estimate |K15 - G7| summed over panels; the azimuth \
    average (E_avg of classic-albedo-aniso) by adaptive Gauss-Kronrod over phi_v in [0, pi/2]; f64 accumulation";

/// The sidecar's `model` object of a classic table.
pub(crate) fn model_json(spec: &TableSpec) -> Value {
    let c = spec.model.classic.as_ref().expect("a classic table");
    let r = c.reflectance(spec.axes[1].coord(0), 1.0);
    let mut v = json!({
        "form": "classic analytic BRDF (not the microfacet form): f as in model.classic.formula",
        "classic": {
            "name": c.name(),
            "formula": r.formula(),
            "source": r.source(),
            "parameters": c,
        },
        "parameter_axis": {
            "axis": "roughness",
            "quantity": c.parameter_quantity().name(),
            "meaning": c.parameter_meaning(),
        },
        "albedo": "view-side: E(v) = int f(l, v) (n.l) dw_l (equal to the energy law's int f(wi, wo) cos theta_o dwo for reciprocal \
            models; the original phong model is not reciprocal)",
    });
    if spec.kind == TableKind::ClassicAlbedoAniso {
        v["anisotropy"] = json!({
            "axis": "anisotropy",
            "parametrization": ANISOTROPY_MAPPING,
            "azimuth": AZIMUTH_HANDLING,
            "tangent": "x = the surface tangent (ward's alpha_x, ashikhmin-shirley's u), y = the bitangent",
        });
    }
    v
}

/// Most trapezoid panels on [0, π/2] of the azimuth average.
const MAX_AZIMUTH_PANELS: usize = 256;

/// The view-azimuth average `(1/2π)∫₀^{2π} E(θ, φ) dφ = (2/π)∫₀^{π/2} E(θ, φ) dφ` (by the
/// symmetry E(φ) = E(−φ) = E(π − φ)) by the trapezoid rule with N = 1, 2, 4, … panels on
/// [0, π/2], reusing the nodes of the previous level and the given E(0) = `e0` and
/// E(π/2) = `ey`. E(φ) is smooth and π-periodic and even, so this is the trapezoid rule
/// of 2N points over a full period, which converges geometrically for an analytic periodic
/// integrand (Trefethen & Weideman 2014, "The exponentially convergent trapezoidal rule",
/// SIAM Review 56(3), §3): |T_2N − T_N| then bounds the error of T_2N, and the level stops
/// when it is at most half the tolerance (at N ≥ 4). The error adds that difference and the
/// largest node error (the weights sum to 1).
fn azimuth_average(m: &dyn Reflectance, theta: f64, e0: Albedo, ey: Albedo, tol: f64) -> Albedo {
    let mut sum_inner = 0.0; // nodes strictly inside (0, π/2), weight 1/N each
    let mut node_err = e0.error.max(ey.error);
    let mut evals = 0u64;
    let mut n = 1usize;
    let mut prev = 0.5 * (e0.value + ey.value);
    loop {
        // the new nodes of level 2n: odd multiples of π/(4n)
        for k in (1..2 * n).step_by(2) {
            let phi = FRAC_PI_2 * k as f64 / (2 * n) as f64;
            let a = directional_albedo(m, theta, phi, tol);
            sum_inner += a.value;
            node_err = node_err.max(a.error);
            evals += a.evals;
        }
        n *= 2;
        let t = (0.5 * (e0.value + ey.value) + sum_inner) / n as f64;
        let diff = (t - prev).abs();
        prev = t;
        if (n >= 4 && diff <= 0.5 * tol) || n >= MAX_AZIMUTH_PANELS {
            return Albedo {
                value: t,
                error: diff + node_err,
                evals,
            };
        }
    }
}

/// The view-side albedo of an isotropic model at parameter `p` by the 1D fast path of
/// [`classic_lobes`](crate::kernels::classic_lobes) where one exists for the model (blinn-phong, modified-phong, phong,
/// ward-gmd): `None` for other models, `Some(Err(evaluations spent))` where its estimate
/// does not reach `tol`, `None` also at cos θv ≤ 0 (left to the laws integrator's own
/// convention there; tables reject that cosine). The lobe weight scales the lobe (its tolerance is divided by it);
/// a Lambert term adds its albedo, exactly its weight.
pub fn fast_albedo(c: &ClassicModel, mu: f64, p: f64, tol: f64) -> Option<Result<Albedo, u64>> {
    let (lambert, weight, lobe) = fast_lobe(c)?;
    if mu.is_nan() || mu <= 0.0 {
        return None;
    }
    if weight == 0.0 {
        return Some(Ok(Albedo {
            value: lambert,
            error: 0.0,
            evals: 0,
        }));
    }
    Some(lobe(mu, p, tol / weight).map(|e| Albedo {
        value: lambert + weight * e.value[0],
        error: weight * e.error[0],
        evals: e.evals,
    }))
}

type Lobe = fn(f64, f64, f64) -> Result<crate::quadrature::Estimate<1>, u64>;

/// The Lambert weight, lobe weight and 1D fast path of a model that has one.
fn fast_lobe(c: &ClassicModel) -> Option<(f64, f64, Lobe)> {
    use crate::kernels::classic_lobes as cl;
    Some(match *c {
        ClassicModel::BlinnPhong { ks } => (0.0, ks, cl::blinn_phong_albedo),
        ClassicModel::ModifiedPhong { kd, ks } => (kd, ks, cl::modified_phong_albedo),
        ClassicModel::Phong { ks } => (0.0, ks, cl::phong_albedo),
        ClassicModel::WardGmd { rho_d, rho_s } => (rho_d, rho_s, cl::ward_gmd_albedo),
        _ => return None,
    })
}

/// The quadrature method of a classic table, as the sidecar states it: the 1D fast path
/// first where the model has one ([`fast_albedo`]), the energy-law integrator otherwise.
pub fn method(spec: &TableSpec) -> String {
    let c = spec.model.classic.as_ref().expect("a classic table");
    if fast_lobe(c).is_none() {
        return METHOD.into();
    }
    let (which, rest) = if spec.kind == TableKind::ClassicAlbedoAniso {
        (
            "the isotropic texels (anisotropy a = 0) first by the 1D fast path: ",
            "every texel with a > 0, and an isotropic texel whose estimate does not reach the tolerance",
        )
    } else {
        (
            "first by the 1D fast path: ",
            "a texel whose estimate does not reach the tolerance",
        )
    };
    format!(
        "{which}{}; {rest}: {METHOD}",
        crate::kernels::classic_lobes::METHOD
    )
}

/// The isotropic view-side albedo of `m` (the model `c` at parameter `p`): the fast path,
/// else the energy-law integrator (counting the evaluations of an abandoned fast attempt).
fn isotropic_albedo(c: &ClassicModel, m: &ViewFixed, mu: f64, p: f64, tol: f64) -> Albedo {
    let spent = match fast_albedo(c, mu, p, tol) {
        Some(Ok(a)) => return a,
        Some(Err(spent)) => spent,
        None => 0,
    };
    let mut a = directional_albedo(m, mu.clamp(0.0, 1.0).acos(), 0.0, tol);
    a.evals += spent;
    a
}

pub(crate) fn texel_fn(spec: &TableSpec) -> Box<dyn Fn([usize; 3]) -> TexelResult + Sync> {
    let c = *spec.model.classic.as_ref().expect("validated");
    let axes = spec.axes.clone();
    let tol = spec.tolerance;
    let aniso = spec.kind == TableKind::ClassicAlbedoAniso;
    Box::new(move |idx| {
        let mu = axes[0].coord(idx[0]);
        let p = axes[1].coord(idx[1]);
        let asp = if aniso {
            aspect(axes[2].coord(idx[2]))
        } else {
            1.0
        };
        let m = ViewFixed(c.reflectance(p, asp));
        let theta = mu.clamp(0.0, 1.0).acos();
        if !aniso || m.isotropic() {
            // (a = 0, or a model that stays isotropic: every azimuth is the same, and the
            // three channels of the 3D kind are the isotropic table's value)
            let e0 = isotropic_albedo(&c, &m, mu, p, tol);
            let n = if aniso { 3 } else { 1 };
            return TexelResult {
                value: vec![e0.value; n],
                error: vec![e0.error; n],
                evals: e0.evals,
            };
        }
        let e0 = directional_albedo(&m, theta, 0.0, tol);
        let ey = directional_albedo(&m, theta, FRAC_PI_2, tol);
        let avg = azimuth_average(&m, theta, e0, ey, tol);
        TexelResult {
            value: vec![avg.value, e0.value, ey.value],
            error: vec![avg.error, e0.error, ey.error],
            evals: avg.evals + e0.evals + ey.evals,
        }
    })
}
