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
//! lights of every size and place, most of which lie in the BRDF's tails, away from its peak
//! (`examples/ltc_check.rs` measures exactly that). A polygon's lit value is an average of
//! `norm·D` over it, so the pointwise ratio `D/y`, `y = f cos/norm`, sets the relative error
//! of a small light there, and lights of all places weigh equally. The objective is thus the
//! solid-angle average of a symmetric relative residual,
//!
//! `E = Σ_k w_k s_k²`, `s_k = (D(l_k) − y_k)/(D(l_k) + y_k)`, `Σ w_k = 1`,
//!
//! over the nodes `l_k` of a fixed rule on the hemisphere ([`HemisphereRule`]; weights the
//! solid angle over 2π). `s = tanh(½ ln(D/y))`: it is `½ ln(D/y)` to first order (factor-2
//! errors either way weigh the same), bounded by 1 where a 4-parameter lobe cannot follow
//! the BRDF at all (Beckmann's exp(−tan²θ/α²) tails: an unbounded log error there would
//! let a handful of hopeless nodes steer the whole fit), and defined where `D` or `y` is 0.
//! The paper's own measure, `∫|f cos − norm·D|³` (Heitz et al. 2016, §4, after its
//! Monte Carlo estimate in `fit/fitLTC.cpp`), weighs the peak alone; it is reported
//! ([`FitReport::l3`]) on the same rule, not minimized.
//!
//! **Which LTCs.** `M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]]`. With `d ≠ 0` the LTC's support
//! is the tilted half-space `d·x + z > 0`, not the upper hemisphere: it is exactly 0 on a
//! wedge above the horizon (lights there come out black: the published tables' exact zeros)
//! and puts `1 − m` of its mass below the horizon (closed form,
//! [`Ltc::upper_hemisphere_mass`]), which lights crossing the horizon pick up. The default
//! fit holds `d = 0` ([`LtcFitOptions::free_d`]): the support is then the upper hemisphere,
//! like the BRDF's. With `d` free, the mass below the horizon enters `E` as one more
//! residual, `(m − 1)/(m + 1)` with weight [`LtcFitOptions::mass_weight`].
//!
//! **The optimizer.** Levenberg–Marquardt ([`ltc_lm`](super::ltc_lm), why there) in the
//! parameters `θ = (ln a, b/a, ln c, d)`: logarithms keep `a, c > 0` and make the widths'
//! steps relative (α spans 10⁻⁵…1, so `a, c` span 1…10⁵), `b/a` is the tangent of the
//! lobe's tilt. The derivatives of `s_k` are analytic (below). A line of texels at one α
//! is fitted from the normal view (where the lobe is rotationally symmetric: `b = d = 0`,
//! `a = c`) toward grazing, each texel starting from the previous one's solution — a fixed
//! path inside one task, so the result does not depend on threads or texel order; the first
//! texel tries a fixed set of widths and keeps the best.
//!
//! **The channels.** `norm` is [`directional_albedo`] itself (brdfbake's albedo tables hold
//! the same number, bit for bit), and the Fresnel channel the Schlick-weighted part
//! `∫ (1 − v·h)⁵ f cos` of the split sum (Karis 2013, eq. 8; Hill 2016, "LTC Fresnel
//! Approximation") by brdfbake's split-sum integrators, so that a shader's
//! `F0·norm + (F90 − F0)·fresnel` is the Schlick-weighted albedo.

use super::ltc_lm::{minimize, LmSettings, Normal};
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
    /// Gauss–Legendre nodes in φ of the objective's rule.
    pub n_phi: usize,
    /// Gauss–Legendre nodes in the inner (θh) variable.
    pub n_u: usize,
    /// Absolute tolerance of the norm and Fresnel integrals.
    pub tolerance: f64,
    /// Fit `d` (the support's tilt) too; otherwise `d = 0`.
    pub free_d: bool,
    /// Weight of the below-horizon mass residual when `free_d` (the node weights add to 1).
    pub mass_weight: f64,
    /// The optimizer's settings.
    pub lm: LmSettings,
}

impl Default for LtcFitOptions {
    fn default() -> Self {
        LtcFitOptions {
            n_phi: 24,
            n_u: 32,
            tolerance: 1e-7,
            free_d: false,
            mass_weight: 1.0,
            lm: LmSettings::default(),
        }
    }
}

/// How well the fitted LTC matches, on the objective's rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitReport {
    /// The minimized objective `E = Σ w s²` (module doc); `√E` is an rms relative error.
    pub objective: f64,
    /// The paper's error `∫ |y − D|³ dω` with `y = f cos/norm`, on the same rule.
    pub l3: f64,
    /// The LTC's mass above the horizon (1 when `d = 0`).
    pub upper_mass: f64,
    /// Residual passes the optimizer spent (all starts).
    pub passes: usize,
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
    pub fit: FitReport,
}

/// The target of one texel: rule directions, normalized weights and `y = f cos/norm`.
struct Target {
    dirs: Vec<[f64; 3]>,
    w: Vec<f64>,
    y: Vec<f64>,
}

impl Target {
    fn new(rule: &HemisphereRule, fcos: &dyn Fn(&Node) -> f64, norm: f64) -> Target {
        let total: f64 = rule.weights.iter().sum();
        let w = rule.weights.iter().map(|x| x / total).collect();
        let y = rule
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
        Target {
            dirs: rule.dirs.clone(),
            w,
            y,
        }
    }
}

/// `θ → (a, b, c, d)`; `None` where that is not an [`Ltc`].
fn ltc_of<const P: usize>(t: &[f64; P]) -> Option<Ltc> {
    let a = t[0].exp();
    let b = t[1] * a;
    let c = t[2].exp();
    let d = if P > 3 { t[3] } else { 0.0 };
    Ltc::new(a, b, c, d).ok()
}

fn theta_of<const P: usize>(l: &Ltc) -> [f64; P] {
    let mut t = [0.0; P];
    t[0] = l.a.ln();
    t[1] = l.b / l.a;
    t[2] = l.c.ln();
    if P > 3 {
        t[3] = l.d;
    }
    t
}

/// The objective's normal equations at θ (module doc). Per node, with `q = M⁻¹l`,
/// `k = a − bd` and `D = q_z·c·k/(π|q|⁴)`:
/// `∂ln D/∂a = 1/k − 4q_x l_x/|q|²`, `∂ln D/∂b = −d/k − 4q_x l_z/|q|²`,
/// `∂ln D/∂c = 1/c − 4q_y l_y/|q|²`, `∂ln D/∂d = l_x/q_z − b/k − 4q_z l_x/|q|²`,
/// `∂s/∂ln D = 2Dy/(D + y)²`; and by the chain rule for θ: `∂/∂ln a = a∂_a + b∂_b`,
/// `∂/∂(b/a) = a∂_b`, `∂/∂ln c = c∂_c`.
fn normal_eq<const P: usize>(
    tg: &Target,
    t: &[f64; P],
    mass_weight: f64,
) -> Option<(Normal<P>, Ltc)> {
    let l = ltc_of(t)?;
    let (a, b, c, d) = (l.a, l.b, l.c, l.d);
    let k = a - b * d;
    let det = c * k;
    let mut n = Normal::<P>::zero();
    for ((dir, &w), &y) in tg.dirs.iter().zip(&tg.w).zip(&tg.y) {
        let q = l.apply_inverse(*dir);
        let sw = w.sqrt();
        if q[2] <= 0.0 {
            // outside the LTC's support: s = −1 (or 0 where y = 0 too), flat in θ
            let s = if y > 0.0 { -1.0 } else { 0.0 };
            n.add(sw * s, &[0.0; P]);
            continue;
        }
        let l2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
        let x = q[2] * det / (PI * l2 * l2);
        let sum = x + y;
        let s = (x - y) / sum;
        let ds = 2.0 * x * y / (sum * sum);
        let i4 = 4.0 / l2;
        let da = 1.0 / k - i4 * q[0] * dir[0];
        let db = -d / k - i4 * q[0] * dir[2];
        let dc = 1.0 / c - i4 * q[1] * dir[1];
        let mut j = [0.0; P];
        j[0] = a * da + b * db;
        j[1] = a * db;
        j[2] = c * dc;
        if P > 3 {
            j[3] = dir[0] / q[2] - b / k - i4 * q[2] * dir[0];
        }
        let f = sw * ds;
        for v in j.iter_mut() {
            *v *= f;
        }
        n.add(sw * s, &j);
    }
    if P > 3 {
        // the below-horizon mass, m = (1 + a/√(a² + d²))/2
        let h2 = a * a + d * d;
        let h = h2.sqrt();
        let m = 0.5 * (1.0 + a / h);
        let dm_da = 0.5 * d * d / (h2 * h);
        let dm_dd = -0.5 * a * d / (h2 * h);
        let sw = mass_weight.sqrt();
        let r = sw * (m - 1.0) / (m + 1.0);
        let dr = sw * 2.0 / ((m + 1.0) * (m + 1.0));
        let mut j = [0.0; P];
        j[0] = dr * a * dm_da;
        j[3] = dr * dm_dd;
        n.add(r, &j);
    }
    n.e.is_finite().then_some((n, l))
}

/// Fits the LTC on a prepared target from `start`.
fn fit_target(tg: &Target, start: &Ltc, opts: &LtcFitOptions) -> Option<(Ltc, f64, usize)> {
    if opts.free_d {
        let r = minimize(
            |t: &[f64; 4]| normal_eq(tg, t, opts.mass_weight).map(|x| x.0),
            theta_of::<4>(start),
            opts.lm,
        )?;
        Some((ltc_of(&r.theta)?, r.e, r.passes))
    } else {
        let s0 = Ltc { d: 0.0, ..*start };
        let s0 = if Ltc::new(s0.a, s0.b, s0.c, 0.0).is_ok() {
            s0
        } else {
            Ltc::IDENTITY
        };
        let r = minimize(
            |t: &[f64; 3]| normal_eq(tg, t, 0.0).map(|x| x.0),
            theta_of::<3>(&s0),
            opts.lm,
        )?;
        Some((ltc_of(&r.theta)?, r.e, r.passes))
    }
}

/// The objective's value and the L³ error of `ltc` on a target.
fn report(tg: &Target, ltc: &Ltc, rule: &HemisphereRule, norm: f64) -> (f64, f64) {
    let total: f64 = rule.weights.iter().sum();
    let (mut e, mut l3) = (0.0, 0.0);
    for ((dir, &w), &y) in tg.dirs.iter().zip(&tg.w).zip(&tg.y) {
        let x = ltc.eval(*dir);
        let s = if x + y > 0.0 { (x - y) / (x + y) } else { 0.0 };
        e += w * s * s;
        let dd = (x - y).abs() * norm;
        l3 += w * total * dd * dd * dd;
    }
    (e, l3)
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
    let tg = Target::new(&rule, fcos, norm);
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
    match start {
        Some(s) => {
            if let Some((l, e, p)) = fit_target(&tg, s, opts) {
                passes += p;
                consider(l, e);
            }
        }
        None => {
            for m in START_WIDTHS {
                let w = (m * scale).min(1.0);
                let s = Ltc {
                    a: 1.0 / w,
                    b: 0.0,
                    c: 1.0 / w,
                    d: 0.0,
                };
                if let Some((l, e, p)) = fit_target(&tg, &s, opts) {
                    passes += p;
                    consider(l, e);
                }
            }
        }
    }
    let Some((ltc, _)) = best else {
        return Err(LtcError::Domain(
            "the fit found no valid LTC (the objective is not finite at any start)".into(),
        ));
    };
    let (objective, l3) = report(&tg, &ltc, &rule, norm);
    Ok((
        ltc,
        FitReport {
            objective,
            l3,
            upper_mass: ltc.upper_hemisphere_mass(),
            passes,
        },
    ))
}

/// `f cos` of a brdfbake BRDF at a half-vector node.
fn brdf_fcos(brdf: &Brdf) -> impl Fn(&Node) -> f64 + '_ {
    let wd = brdf.diffuse_weight / PI;
    move |n: &Node| brdf.specular.as_ref().map_or(0.0, |s| s.cosine_weighted(n)) + wd * n.n_dot_l
}

/// The lobe warp of a BRDF (its specular lobe's; a Lambertian one is a unit-width lobe).
fn brdf_warp(brdf: &Brdf) -> LobeWarp {
    brdf.specular
        .as_ref()
        .map_or(LobeWarp::TanOverScale(1.0), |s| s.warp())
}

/// `(norm, its error, fresnel, its error)` of a BRDF at view cosine `mu`: the norm by
/// [`directional_albedo`], the Fresnel channel by the split-sum kernels for a specular lobe
/// with F = 1 and no diffuse lobe ([`split_sum_kernels`]), else by the hemisphere rule
/// ([`integrate_over_l_smooth`]) of `(1 − v·h)⁵ f cos`. Each inside its own evaluation budget.
pub fn norm_and_fresnel(brdf: &Brdf, mu: f64, tol: f64) -> (f64, f64, f64, f64) {
    let (n, ne, _) = with_budget(INTEGRAL_EVAL_BUDGET, || directional_albedo(brdf, mu, tol));
    let (f, fe) = with_budget(INTEGRAL_EVAL_BUDGET, || match &brdf.specular {
        Some(s) if brdf.diffuse_weight == 0.0 && s.fresnel == Fresnel::None => {
            let (v, e, _) = split_sum_kernels(s, mu, tol);
            (v[1], e[1])
        }
        _ => {
            let g = brdf_fcos(brdf);
            let e = integrate_over_l_smooth(mu, brdf.specular.as_ref().map(|s| &s.ndf), tol, |n| {
                [g(n) * schlick_weight(n.v_dot_h)]
            });
            (e.value[0], e.error[0])
        }
    });
    (n[0], ne[0], f, fe)
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
    let (norm, norm_error, fresnel, fresnel_error) = norm_and_fresnel(brdf, mu, opts.tolerance);
    let fcos = brdf_fcos(brdf);
    let (ltc, fit) = fit_ltc(&fcos, mu, brdf_warp(brdf), norm, start, shape, opts)?;
    Ok(LtcTexel {
        ltc,
        norm,
        fresnel,
        norm_error,
        fresnel_error,
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
    let shape = RuleShape::new(opts.n_phi, opts.n_u);
    let lines: Vec<Result<Vec<LtcTexel>, LtcError>> = alphas
        .par_iter()
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
