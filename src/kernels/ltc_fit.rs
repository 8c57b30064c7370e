//! The deterministic LTC fit of one texel (view cosine μ, roughness α), of a line of texels,
//! and of a whole (view × roughness) grid.
//!
//! **What is fitted.** For a BRDF `f` and view `v`, the table stores an LTC `D` (its `M⁻¹`,
//! [`Ltc`]) with `f(v, l)·(n·l) ≈ norm·D(l)`, `norm = ∫ f cos` the directional albedo
//! (Heitz et al. 2016, §4: "we fit … the normalized BRDF and store its norm separately").
//! The lit value of a polygonal light `P` is then `norm·∫_P D` in closed form
//! ([`ltc_polygon_integral`](crate::kernels::ltc_polygon::ltc_polygon_integral)).
//!
//! **The error measure.** What a user sees is the relative error of that lit value, over
//! lights of every size and place (`examples/ltc_check.rs` measures exactly that: 200
//! lights × 10 views × 10 roughnesses against a quadrature ground truth). Most lights lie in
//! the BRDF's tails, where a lit value's error is its overestimate or underestimate of a
//! small number, and the bright ones hold the specular peak, where it is the lobe's shape.
//! The objective is a weighted sum of squared *relative* residuals `(X − Y)/(Y + ε·Ω)` —
//! an LTC's value `X` against the BRDF's `Y` over a region of solid angle `Ω`, `ε` a floor
//! ([`LtcFitOptions::floor`]) below which a density is taken as 0 — of three kinds:
//! * the nodes `l_k` of a fixed rule on the hemisphere ([`HemisphereRule`]), pointwise
//!   (`X = D(l_k)`, `Y = y_k = f cos/norm`), weighted by their solid angle (`dω_k/2π`, the
//!   tails) plus `λ` times the BRDF's energy there (`λ·y_k dω_k`, the peak's shape;
//!   `λ` = [`LtcFitOptions::energy_weight`]);
//! * probe lights ([`super::ltc_probe`]): a fixed tiling of the hemisphere into spherical
//!   quads and two bands straddling the horizon, `X` the LTC's lit value in closed form,
//!   weighted by solid angle. They see what no node can: a narrow ridge of LTC mass between
//!   nodes (a sheared lobe at grazing views puts one along the horizon on the viewer's side:
//!   lights there came out ×10⁴ too bright when only nodes were fitted) and the mass an LTC
//!   with `d < 0` puts below the horizon, which a light crossing the horizon picks up.
//!
//! The residual is the lit value's relative error itself: unbounded above (a light lit
//! 100× too bright is as wrong as the measure says) and at most 1 below (an unlit light).
//! That asks the LTC to follow the lobe down to the floor, which an LTC can for GGX (both
//! fall off as a power of the angle from their axis) but not for a lobe that falls faster
//! or vanishes inside (Beckmann's Gaussian tails, Charlie sheen's empty centre): there
//! every direction costs `X/(εΩ)` and the cheapest LTC was a razor at the parameter box.
//! For those the table raises the floor to the lobe's peak density
//! ([`LtcFitOptions::peak_floor`]; `table::ltc::fit_options` says which lobes and why),
//! which makes the residual an absolute error in units of the peak away from it.
//! The paper's own measure, `∫|f cos − norm·D|³` (Heitz et al. 2016, §4, after its
//! Monte Carlo estimate in `fit/fitLTC.cpp`), weighs the peak alone; it is reported
//! ([`FitReport::l3`]) on the same rule, not minimized.
//!
//! **Which LTCs.** `M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]]` with `b ≥ 0 ≥ d` (the bounds'
//! doc says why: every bilinear lookup between texels stays invertible). With `d < 0` the
//! LTC's support is the tilted half-space `d·x + z > 0`: it is 0 on a wedge above the
//! horizon on the viewer's side (lights there come out black: the published tables'
//! exact zeros) and puts `1 − m` of its mass below the horizon on the mirror side (closed
//! form, [`Ltc::upper_hemisphere_mass`]). What it buys is the lobe's shape down to the
//! horizon on the mirror side, which `d = 0` (a sheared cosine, which must vanish at the
//! horizon like `z`) cannot follow: with `d = 0` ([`LtcFitOptions::free_d`] false) a
//! light holding the specular peak had twice the median error. The probes set the trade.
//!
//! **The optimizer.** Projected Levenberg–Marquardt ([`ltc_lm`](super::ltc_lm), why there)
//! in `θ = (ln a, b/a, ln c, d)`: logarithms keep `a, c > 0` and make the widths' steps
//! relative (α spans 10⁻⁵…1, so `a, c` span 1…10⁵), `b/a` is the cotangent of the lobe
//! axis' elevation. The derivatives are analytic (the nodes' below, the probes' in
//! [`super::ltc_probe`]). A line of texels at one α is fitted from the normal view toward
//! grazing, each texel starting from the better (by the objective) of the previous texel's
//! LTC and a mirror-lobe guess (`mirror_guess`); the line's first texel tries the guess
//! and a fixed set of widths. A fixed path inside one task: the result does not depend on
//! threads or texel order.
//!
//! **The channels.** `norm` is [`directional_albedo`] itself (brdfbake's albedo tables hold
//! the same number, bit for bit), and the Fresnel channel the Schlick-weighted part
//! `∫ (1 − v·h)⁵ f cos` of the split sum (Karis 2013, eq. 8; Hill 2016, "LTC Fresnel
//! Approximation") by brdfbake's split-sum integrators, so that a shader's
//! `F0·norm + (F90 − F0)·fresnel` is the Schlick-weighted albedo.

use super::ltc_lm::{minimize, LmSettings, Normal};
use super::ltc_probe::{ltc_probe, probes, Probe};
use super::ltc_rule::{HemisphereRule, RuleShape};
use crate::hemisphere::tensor::integrate_over_l_smooth;
use crate::hemisphere::{LobeWarp, Node};
use crate::model::fresnel::schlick_weight;
use crate::model::ltc::{Ltc, LtcError};
use crate::model::{Brdf, Fresnel};
use crate::quadrature::budget::{with_budget, INTEGRAL_EVAL_BUDGET};
use crate::table::albedo::directional_albedo;
use crate::table::dfg::split_sum_kernels;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Settings of the fit.
#[derive(Clone, Copy, Debug)]
pub struct LtcFitOptions {
    /// The objective's rule: φ panels, Gauss–Legendre nodes per φ panel, inner panels,
    /// nodes per inner panel ([`RuleShape::new`]).
    pub rule: [usize; 4],
    /// Absolute tolerance of the norm and Fresnel integrals.
    pub tolerance: f64,
    /// Fit `d` (the tilt of the LTC's support) too; otherwise `d = 0`.
    pub free_d: bool,
    /// Weight of the nodes' solid-angle term: node k weighs `point_weight·dω_k/2π`.
    pub point_weight: f64,
    /// Weight of the nodes' energy term: node k weighs `energy_weight·y_k·dω_k`.
    pub energy_weight: f64,
    /// Weight of the probe lights ([`super::ltc_probe`]): probe p weighs
    /// `probe_weight·Ω_p/2π`.
    pub probe_weight: f64,
    /// The floor ε of the relative residual `(X − Y)/(Y + εΩ)`, a density per steradian of
    /// the normalized lobe.
    pub floor: f64,
    /// The floor relative to the lobe's peak: a texel's floor is
    /// `max(floor, peak_floor·y_max)`, `y_max` the normalized lobe's largest value on the
    /// fit's rule (0: the absolute floor alone).
    pub peak_floor: f64,
    /// The lobe leans toward the view (a sheen lobe's back-scatter): the box's signs are
    /// `b ≤ 0 ≤ d` instead of `b ≥ 0 ≥ d` (see the bounds' doc).
    pub retro: bool,
    /// The optimizer's settings.
    pub lm: LmSettings,
}

impl Default for LtcFitOptions {
    fn default() -> Self {
        LtcFitOptions {
            rule: [6, 3, 6, 4],
            tolerance: 1e-7,
            free_d: true,
            point_weight: 1.0,
            energy_weight: 10.0,
            probe_weight: 1.0,
            floor: 1e-9,
            peak_floor: 0.0,
            retro: false,
            lm: LmSettings::default(),
        }
    }
}

impl LtcFitOptions {
    /// The rule's shape.
    pub fn shape(&self) -> RuleShape {
        let [a, b, c, d] = self.rule;
        RuleShape::new(a, b, c, d)
    }
}

/// How well the fitted LTC matches, on the objective's rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitReport {
    /// The minimized objective (module doc); `√objective` is an rms relative error.
    pub objective: f64,
    /// The paper's error `∫ |f cos − norm·D|³ dω`, on the same rule (per steradian³ of
    /// `f cos`: it grows as `α⁻⁴` for narrow lobes).
    pub l3: f64,
    /// [`FitReport::l3`] over `∫ (f cos)³ dω` on the same rule: dimensionless, comparable
    /// across texels.
    pub l3_relative: f64,
    /// Residual passes the optimizer spent (all starts).
    pub passes: usize,
    /// The relative error of the lit value of the probe lights ([`super::ltc_probe`]: the
    /// fixed tiling of the hemisphere into spherical quads and the two bands across the
    /// horizon, less the quad holding the BRDF's peak and those whose BRDF value the probe
    /// rules do not resolve), `r_p = (X_p − Y_p)/(Y_p + ε·Ω_p)` with `X` the LTC's closed
    /// form and `Y` the BRDF's: the root mean square weighted by solid angle.
    pub lit_rms: f64,
    /// The largest `|r_p|` over the probes that hold at least 1% of the brightest probe's
    /// lit value (the lights that matter; the dim ones are in [`FitReport::lit_rms`]).
    pub lit_max: f64,
}

/// `(lit_rms, lit_max)` of [`FitReport`] for `ltc` on a target.
fn lit_errors(tg: &Target, ltc: &Ltc) -> (f64, f64) {
    let brightest = tg.probes.iter().map(|p| p.y).fold(0.0, f64::max);
    let (mut sum, mut omega, mut max) = (0.0, 0.0, 0.0f64);
    for p in &tg.probes {
        let (x, _) = ltc_probe(ltc, &p.verts);
        let r = (x - p.y) / (p.y + tg.floor * p.omega);
        sum += p.omega * r * r;
        omega += p.omega;
        if p.y >= 0.01 * brightest {
            max = max.max(r.abs());
        }
    }
    let rms = if omega > 0.0 {
        (sum / omega).sqrt()
    } else {
        0.0
    };
    (rms, max)
}

/// One fitted texel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LtcTexel {
    pub ltc: Ltc,
    /// `∫ f cos`, brdfbake's directional albedo.
    pub norm: f64,
    /// `∫ (1 − v·h)⁵ f cos`.
    pub fresnel: f64,
    /// The quadratures' error estimates of `norm` and `fresnel`.
    pub norm_error: f64,
    pub fresnel_error: f64,
    /// Integrand evaluations of the BRDF: the norm and Fresnel quadratures, the fit's rule
    /// and its probe lights' rules (the LTC's own evaluations are not counted).
    pub evaluations: u64,
    pub fit: FitReport,
}

impl LtcTexel {
    /// A texel with no fit: the clamped cosine (M⁻¹ = I) beside the norm and Fresnel
    /// channels `nf`, for lobes with nothing to fit (a pure Lambertian lobe, or nothing
    /// reflected).
    pub fn unfitted(nf: NormFresnel) -> LtcTexel {
        LtcTexel {
            ltc: Ltc::IDENTITY,
            norm: nf.norm,
            fresnel: nf.fresnel,
            norm_error: nf.norm_error,
            fresnel_error: nf.fresnel_error,
            evaluations: nf.evaluations,
            fit: FitReport {
                objective: 0.0,
                l3: 0.0,
                l3_relative: 0.0,
                passes: 0,
                lit_rms: 0.0,
                lit_max: 0.0,
            },
        }
    }
}

/// The number of parameters: `(ln a, b/a, ln c, d)`.
const P: usize = 4;

/// The target of one texel on its rule.
struct Target {
    dirs: Vec<[f64; 3]>,
    /// Per node: `y = f cos/norm` and the node's weight.
    y: Vec<f64>,
    w: Vec<f64>,
    probes: Vec<Probe>,
    probe_weight: f64,
    floor: f64,
    free_d: bool,
}

impl Target {
    fn new(
        rule: &HemisphereRule,
        v: [f64; 3],
        fcos: &dyn Fn(&Node) -> f64,
        norm: f64,
        opts: &LtcFitOptions,
    ) -> Target {
        let y: Vec<f64> = rule
            .nodes
            .iter()
            .map(|n| {
                let v = fcos(n) / norm;
                if v.is_finite() {
                    v.max(0.0)
                } else {
                    0.0
                }
            })
            .collect();
        let w: Vec<f64> = rule
            .weights
            .iter()
            .zip(&y)
            .map(|(&dw, &yk)| opts.point_weight * dw / (2.0 * PI) + opts.energy_weight * dw * yk)
            .collect();
        let y_max = y.iter().copied().fold(0.0, f64::max);
        let floor = opts.floor.max(opts.peak_floor * y_max);
        let probes = if opts.probe_weight > 0.0 {
            // the BRDF's peak among the nodes
            let peak = y
                .iter()
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(b.1).then(b.0.cmp(&a.0)))
                .map(|(k, _)| rule.dirs[k]);
            probes(v, fcos, norm, peak, floor)
        } else {
            Vec::new()
        };
        Target {
            dirs: rule.dirs.clone(),
            y,
            w,
            probes,
            probe_weight: opts.probe_weight,
            floor,
            free_d: opts.free_d,
        }
    }
}

/// The box the parameters stay in: `a`, `c` within `[10⁻⁶, 10⁹]` (lobe widths from 10⁻⁹ to
/// 10⁶ rad: beyond every lobe a table holds), the axis' tilt `b/a` within `[0, 10⁶]`
/// (leaning toward the mirror side, at least 10⁻⁶ rad above the horizon) and the
/// support's tilt `d` within `[−20, 0]`. The signs are what keeps a table usable between
/// its texels: a shader interpolates the stored `(a, d, b, 1)/c` linearly, and with
/// `b ≥ 0 ≥ d` at every texel every interpolated `M⁻¹` has `det/c = (a + b·|d|)/c² > 0`
/// (each factor keeps its sign under convex combinations); with mixed signs two valid
/// neighbours can interpolate to a singular matrix (seen: thousands of lookups in a 64²
/// table fitted without them). A lobe that leans toward the view ([`LtcFitOptions::retro`]:
/// Charlie sheen, whose fitted axis lies on the view's side, `b < 0`, and whose support
/// tilts the other way, `d > 0`) takes the mirror box, `b ≤ 0 ≤ d` (`b/a ∈ [−10⁶, 0]`,
/// `d ∈ [0, 20]`), where `det/c = (a + |b|·d)/c² > 0` holds between texels all the same.
const LN_MIN: f64 = -13.815510557964274; // ln 1e-6
const LN_MAX: f64 = 20.72326583694641; // ln 1e9
const TILT_MAX: f64 = 1e6;
const D_MIN: f64 = -20.0;

/// The box as `(lower, upper)` bounds of θ; `d` is held at 0 without `free_d`; the signs
/// of `b` and `d` swapped with `retro`.
fn bounds(free_d: bool, retro: bool) -> ([f64; P], [f64; P]) {
    let dlo = if free_d { D_MIN } else { 0.0 };
    if retro {
        (
            [LN_MIN, -TILT_MAX, LN_MIN, 0.0],
            [LN_MAX, 0.0, LN_MAX, -dlo],
        )
    } else {
        ([LN_MIN, 0.0, LN_MIN, dlo], [LN_MAX, TILT_MAX, LN_MAX, 0.0])
    }
}

/// `θ → (a, b, c, d)`; `None` where that is not an [`Ltc`].
fn ltc_of(t: &[f64; P]) -> Option<Ltc> {
    if !t.iter().all(|x| x.is_finite()) {
        return None;
    }
    let a = t[0].exp();
    Ltc::new(a, t[1] * a, t[2].exp(), t[3]).ok()
}

fn theta_of(l: &Ltc) -> [f64; P] {
    [l.a.ln(), l.b / l.a, l.c.ln(), l.d]
}

/// The objective's normal equations at θ (module doc). Per node, with `q = M⁻¹l`,
/// `k = a − bd` and `D = q_z·ck/(π|q|⁴)`: `∂ln D/∂a = 1/k − 4q_x l_x/|q|²`,
/// `∂ln D/∂b = −d/k − 4q_x l_z/|q|²`, `∂ln D/∂c = 1/c − 4q_y l_y/|q|²`,
/// `∂ln D/∂d = l_x/q_z − b/k − 4q_z l_x/|q|²`; for θ by the chain rule `∂/∂ln a = a∂_a +
/// b∂_b`, `∂/∂(b/a) = a∂_b`, `∂/∂ln c = c∂_c`. Where `q_z ≤ 0` (outside the support) the
/// residual is `−y/(y + ε)`, flat in θ. A probe's residual `(X − Y)/(Y + εΩ)` has the
/// gradient of `X` ([`ltc_probe`]) over `Y + εΩ`. Without `free_d` the d column is 0, so
/// the solver never moves d.
fn normal_eq(tg: &Target, t: &[f64; P]) -> Option<(Normal<P>, Ltc)> {
    let l = ltc_of(t)?;
    let (a, b, c, d) = (l.a, l.b, l.c, l.d);
    let k = a - b * d;
    let det = c * k;
    let dmask = if tg.free_d { 1.0 } else { 0.0 };
    let mut n = Normal::<P>::zero();
    for (i, dir) in tg.dirs.iter().enumerate() {
        let y = tg.y[i];
        let den = y + tg.floor;
        let sw = tg.w[i].sqrt();
        let q = l.apply_inverse(*dir);
        if q[2] <= 0.0 {
            n.add(-sw * y / den, &[0.0; P]);
            continue;
        }
        let l2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
        let x = q[2] * det / (PI * l2 * l2);
        let i4 = 4.0 / l2;
        let da = 1.0 / k - i4 * q[0] * dir[0];
        let db = -d / k - i4 * q[0] * dir[2];
        let dc = 1.0 / c - i4 * q[1] * dir[1];
        let dd = dir[0] / q[2] - b / k - i4 * q[2] * dir[0];
        let f = sw * x / den;
        n.add(
            sw * (x - y) / den,
            &[
                f * (a * da + b * db),
                f * a * db,
                f * c * dc,
                f * dd * dmask,
            ],
        );
    }
    for p in &tg.probes {
        let (x, g) = ltc_probe(&l, &p.verts);
        let den = p.y + tg.floor * p.omega;
        let sw = (tg.probe_weight * p.omega / (2.0 * PI)).sqrt();
        let f = sw / den;
        n.add(
            f * (x - p.y),
            &[f * g[0], f * g[1], f * g[2], f * g[3] * dmask],
        );
    }
    n.e.is_finite().then_some((n, l))
}

/// Fits the LTC on a prepared target from `start` (with `d = 0` unless `free_d`).
fn fit_target(tg: &Target, start: &Ltc, opts: &LtcFitOptions) -> Option<(Ltc, f64, usize)> {
    let s0 = Ltc::new(start.a, start.b, start.c, start.d).unwrap_or(Ltc::IDENTITY);
    let r = minimize(
        |t: &[f64; P]| normal_eq(tg, t).map(|x| x.0),
        theta_of(&s0),
        bounds(opts.free_d, opts.retro),
        opts.lm,
    )?;
    Some((ltc_of(&r.theta)?, r.e, r.passes))
}

/// The L³ error of `ltc` on a target (per steradian of `f cos`, not of the normalized lobe).
/// Returns `(∫|f cos − norm·D|³, ∫ (f cos)³)` on the rule.
fn l3_error(tg: &Target, rule: &HemisphereRule, ltc: &Ltc, norm: f64) -> (f64, f64) {
    let (mut l3, mut y3) = (0.0, 0.0);
    for ((dir, &dw), &y) in tg.dirs.iter().zip(&rule.weights).zip(&tg.y) {
        let d = (ltc.eval(*dir) - y).abs() * norm;
        l3 += dw * d * d * d;
        let yn = y * norm;
        y3 += dw * yn * yn * yn;
    }
    (l3, y3)
}

/// The LTC whose lobe sits on the mirror direction of a microfacet lobe of angular width
/// `scale`: with the mirror at elevation `e₀` (`sin e₀ = μ`), `M⁻¹ = [[a, 0, b], [0, c, 0],
/// [0, 0, 1]]` puts the cosine's peak where `ax + bz = 0` (so `b = a·cot e₀`), with angular
/// half-width `sin²e₀/a` in the plane of incidence and `sin e₀/c` across it (expanding
/// `M⁻¹ω` about the axis). A microfacet lobe of width α about h = n reflects to widths
/// `2α` in the plane (a rotation of h turns l twice as far) and `2μα` across it
/// (`δl = 2(v·h)δh` for δh ⊥ the plane, and v·h = μ at h = n), hence
/// `a = μ²/(2α)`, `b = μ√(1 − μ²)/(2α)`, `c = 1/(2α)` (derived here).
fn mirror_guess(mu: f64, scale: f64) -> Ltc {
    let s = scale.clamp(1e-9, 0.5);
    let a = (mu * mu / (2.0 * s)).max(1e-9);
    let b = mu * (1.0 - mu * mu).max(0.0).sqrt() / (2.0 * s);
    let c = 1.0 / (2.0 * s);
    Ltc::new(a, b, c, 0.0).unwrap_or(Ltc::IDENTITY)
}

/// Widths tried at the start of a line: LTCs `diag(1/m, 1/m, 1)` with `m` these multiples
/// of the lobe's scale (capped at 1).
const START_WIDTHS: [f64; 5] = [0.5, 1.0, 2.0, 4.0, 8.0];

/// Fits the LTC of `f cos` (given at half-vector nodes: `fcos(node) = f(v, l)·(n·l)`) at
/// view cosine `mu` ∈ (0, 1], with `norm` = `∫ f cos` and the lobe's warp (`scale`: its
/// angular width, for the first guesses), from `start` or, without one, from the best of
/// the fixed first guesses. Returns the LTC and its report.
pub fn fit_ltc(
    fcos: &dyn Fn(&Node) -> f64,
    mu: f64,
    warp: LobeWarp,
    norm: f64,
    start: Option<&Ltc>,
    shape: &RuleShape,
    opts: &LtcFitOptions,
) -> Result<(Ltc, FitReport), LtcError> {
    if !(mu > 0.0 && mu <= 1.0) {
        return Err(LtcError::Domain(format!(
            "the view cosine must be in (0, 1], got {mu}"
        )));
    }
    if !(norm > 0.0 && norm.is_finite()) {
        return Err(LtcError::Domain(format!(
            "the BRDF's albedo must be > 0 and finite to fit an LTC, got {norm}"
        )));
    }
    let rule = HemisphereRule::new(shape, mu, warp);
    if rule.is_empty() {
        return Err(LtcError::Domain("the hemisphere rule has no nodes".into()));
    }
    let v = [(1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu];
    let tg = Target::new(&rule, v, fcos, norm, opts);
    let scale = match warp {
        LobeWarp::TanOverScale(s) | LobeWarp::TanOverScaleVGroove(s) => s,
        LobeWarp::SheenFlank(_) | LobeWarp::Linear => 1.0,
    };
    let mut passes = 0;
    let mut best: Option<(Ltc, f64)> = None;
    let mut consider = |l: Ltc, e: f64| {
        if best.as_ref().is_none_or(|b| e < b.1) {
            best = Some((l, e));
        }
    };
    // the starts: the mirror-lobe guess (module doc) and the previous texel's LTC, or the
    // fixed widths at a line's first texel; the optimizer runs from the best of them
    let mut starts = vec![mirror_guess(mu, scale)];
    match start {
        Some(s) => starts.push(*s),
        None => {
            for m in START_WIDTHS {
                let w = (m * scale).min(1.0);
                starts.push(Ltc {
                    a: 1.0 / w,
                    b: 0.0,
                    c: 1.0 / w,
                    d: 0.0,
                });
            }
        }
    }
    let mut first: Option<(Ltc, f64)> = None;
    for s0 in &starts {
        let t = theta_of(s0);
        if let Some((n, l)) = normal_eq(&tg, &t) {
            passes += 1;
            if first.as_ref().is_none_or(|b| n.e < b.1) {
                first = Some((l, n.e));
            }
        }
    }
    if let Some((s0, _)) = first {
        if let Some((l, e, p)) = fit_target(&tg, &s0, opts) {
            passes += p;
            consider(l, e);
        }
    }
    let Some((ltc, objective)) = best else {
        return Err(LtcError::Domain(
            "the fit found no valid LTC (the objective is not finite at any start)".into(),
        ));
    };
    let (lit_rms, lit_max) = lit_errors(&tg, &ltc);
    let (l3, y3) = l3_error(&tg, &rule, &ltc, norm);
    Ok((
        ltc,
        FitReport {
            objective,
            l3,
            l3_relative: if y3 > 0.0 { l3 / y3 } else { 0.0 },
            passes,
            lit_rms,
            lit_max,
        },
    ))
}

/// The fit's objective at a given LTC (with `d` as given): how another table's texel fares
/// under the same measure.
pub fn objective_at(
    fcos: &dyn Fn(&Node) -> f64,
    mu: f64,
    warp: LobeWarp,
    norm: f64,
    ltc: &Ltc,
    shape: &RuleShape,
    opts: &LtcFitOptions,
) -> Result<f64, LtcError> {
    if !(mu > 0.0 && mu <= 1.0 && norm > 0.0 && norm.is_finite()) {
        return Err(LtcError::Domain(format!(
            "objective_at needs mu in (0, 1] and norm > 0, got {mu}, {norm}"
        )));
    }
    let rule = HemisphereRule::new(shape, mu, warp);
    let v = [(1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu];
    let tg = Target::new(&rule, v, fcos, norm, opts);
    normal_eq(&tg, &theta_of(ltc))
        .map(|(n, _)| n.e)
        .ok_or_else(|| LtcError::Domain("the LTC is outside the fit's parameter box".into()))
}

/// `f cos` of a brdfbake BRDF at a half-vector node.
pub fn brdf_fcos(brdf: &Brdf) -> impl Fn(&Node) -> f64 + '_ {
    move |n: &Node| {
        brdf.specular.as_ref().map_or(0.0, |s| s.cosine_weighted(n))
            + brdf.diffuse_cosine_weighted(n)
    }
}

/// The lobe warp of a BRDF (its specular lobe's; a Lambertian one is a unit-width lobe).
fn brdf_warp(brdf: &Brdf) -> LobeWarp {
    brdf.specular
        .as_ref()
        .map_or(LobeWarp::TanOverScale(1.0), |s| s.warp())
}

/// The norm and Fresnel channels of one texel, with their quadratures' error estimates and
/// the integrand evaluations they cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormFresnel {
    pub norm: f64,
    pub norm_error: f64,
    pub fresnel: f64,
    pub fresnel_error: f64,
    pub evaluations: u64,
}

/// The norm and Fresnel channels of a BRDF at view cosine `mu`: the norm by
/// [`directional_albedo`], the Fresnel channel by the split-sum kernels for a specular lobe
/// with F = 1 and no diffuse lobe ([`split_sum_kernels`]), else by the hemisphere rule
/// ([`integrate_over_l_smooth`]) of `(1 − v·h)⁵ f cos`. Each inside its own evaluation budget.
pub fn norm_and_fresnel(brdf: &Brdf, mu: f64, tol: f64) -> NormFresnel {
    let (n, ne, n_evals) = with_budget(INTEGRAL_EVAL_BUDGET, || directional_albedo(brdf, mu, tol));
    let (f, fe, f_evals) = with_budget(INTEGRAL_EVAL_BUDGET, || match &brdf.specular {
        Some(s) if brdf.diffuse_weight == 0.0 && s.fresnel == Fresnel::None => {
            let (v, e, evals) = split_sum_kernels(s, mu, tol);
            (v[1], e[1], evals)
        }
        _ => {
            let g = brdf_fcos(brdf);
            let e = integrate_over_l_smooth(mu, brdf.specular.as_ref().map(|s| &s.ndf), tol, |n| {
                [g(n) * schlick_weight(n.v_dot_h)]
            });
            (e.value[0], e.error[0], e.evals)
        }
    });
    NormFresnel {
        norm: n[0],
        norm_error: ne[0],
        fresnel: f,
        fresnel_error: fe,
        evaluations: n_evals + f_evals,
    }
}

/// Fits one texel of a brdfbake BRDF at view cosine `mu` ∈ (0, 1]: the LTC (from `start`,
/// or the fixed first guesses), the norm and the Fresnel channel.
pub fn fit_texel(
    brdf: &Brdf,
    mu: f64,
    start: Option<&Ltc>,
    shape: &RuleShape,
    opts: &LtcFitOptions,
) -> Result<LtcTexel, LtcError> {
    if !(mu > 0.0 && mu <= 1.0) {
        return Err(LtcError::Domain(format!(
            "the view cosine must be in (0, 1], got {mu}"
        )));
    }
    let nf = norm_and_fresnel(brdf, mu, opts.tolerance);
    if nf.norm <= opts.tolerance {
        // nothing is reflected, to the table's tolerance (a sheen lobe of tiny α seen from
        // above: its albedo is 2·10⁻¹⁵⁶ at α = 10⁻³, underflows to 0 or comes out as rounding
        // below 0, −9·10⁻¹³ for Conty–Kulla's at α = 10⁻⁵): every lit value, at most `norm`,
        // is within the tolerance of 0 whatever the matrix, and a fit to such a lobe ran
        // into the parameter box (cond 10⁶ at α = 10⁻³). The texel keeps the clamped cosine,
        // which interpolates with its neighbours as well as any, and the norm channel
        // brdfbake's albedo as it is
        return Ok(LtcTexel::unfitted(nf));
    }
    let fcos = brdf_fcos(brdf);
    let (ltc, fit) = fit_ltc(&fcos, mu, brdf_warp(brdf), nf.norm, start, shape, opts)?;
    Ok(LtcTexel {
        ltc,
        norm: nf.norm,
        fresnel: nf.fresnel,
        norm_error: nf.norm_error,
        fresnel_error: nf.fresnel_error,
        evaluations: nf.evaluations + (shape.len() + super::ltc_probe::brdf_evaluations()) as u64,
        fit,
    })
}

/// The texels of one roughness at the views `mus` (in the given order), fitted along the
/// fixed path from the largest μ to the smallest, each from its predecessor's LTC.
pub fn fit_line(
    brdf: &Brdf,
    mus: &[f64],
    shape: &RuleShape,
    opts: &LtcFitOptions,
) -> Result<Vec<LtcTexel>, LtcError> {
    let mut order: Vec<usize> = (0..mus.len()).collect();
    // descending μ; ties by index (a total order: the path is a function of the inputs)
    order.sort_by(|&i, &j| mus[j].total_cmp(&mus[i]).then(i.cmp(&j)));
    let mut out: Vec<Option<LtcTexel>> = vec![None; mus.len()];
    let mut prev: Option<Ltc> = None;
    for i in order {
        let t = fit_texel(brdf, mus[i], prev.as_ref(), shape, opts)?;
        prev = Some(t.ltc);
        out[i] = Some(t);
    }
    Ok(out
        .into_iter()
        .map(|t| t.expect("every index visited"))
        .collect())
}

/// A fitted (view × roughness) grid.
#[derive(Clone, Debug)]
pub struct LtcGrid {
    pub mus: Vec<f64>,
    pub alphas: Vec<f64>,
    /// Texel `(i_mu, i_alpha)` at `i_mu·alphas.len() + i_alpha` (view-major, roughness
    /// fastest: the order of Heitz's tables).
    pub texels: Vec<LtcTexel>,
}

impl LtcGrid {
    pub fn get(&self, i_mu: usize, i_alpha: usize) -> Option<&LtcTexel> {
        if i_mu >= self.mus.len() || i_alpha >= self.alphas.len() {
            return None;
        }
        self.texels.get(i_mu * self.alphas.len() + i_alpha)
    }
}

/// Fits every texel of the grid `mus × alphas` for the BRDF `model(α)`, one line (one α)
/// per rayon task. Bit-identical on any thread count: a line is a fixed sequence of
/// operations on its own inputs, and rayon only decides which thread runs it.
pub fn fit_grid(
    model: &(dyn Fn(f64) -> Result<Brdf, String> + Sync),
    mus: &[f64],
    alphas: &[f64],
    opts: &LtcFitOptions,
) -> Result<LtcGrid, LtcError> {
    let shape = opts.shape();
    let lines: Vec<Result<Vec<LtcTexel>, LtcError>> = alphas
        .par_iter()
        .with_max_len(1)
        .map(|&alpha| {
            let brdf = model(alpha).map_err(LtcError::Domain)?;
            if let Some(s) = &brdf.specular {
                s.prepare();
            }
            fit_line(&brdf, mus, &shape, opts)
        })
        .collect();
    let mut by_alpha = Vec::with_capacity(alphas.len());
    for l in lines {
        by_alpha.push(l?);
    }
    let mut texels = Vec::with_capacity(mus.len() * alphas.len());
    for i in 0..mus.len() {
        for line in &by_alpha {
            texels.push(line[i]);
        }
    }
    Ok(LtcGrid {
        mus: mus.to_vec(),
        alphas: alphas.to_vec(),
        texels,
    })
}
