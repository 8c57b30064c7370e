//! The area-light kinds: `ltc`, linearly transformed cosines over (cos θv; roughness)
//! (Heitz, Dupuy, Hill & Neubelt 2016), and `ltc-sphere`, the horizon-clipped sphere table
//! (Heitz & Hill 2017).
//!
//! **`ltc`.** Per texel `(μ, α)`: the LTC fitted to the BRDF's `f cos` by
//! [`crate::kernels::ltc_fit`] (deterministic: Levenberg–Marquardt on a fixed rule and fixed
//! probe lights, warm-started along a fixed path: the views of one roughness from the
//! largest μ down, one roughness per task, so the bits do not depend on the thread count),
//! and the channels the preset's `ltc.channels` lists ([`LtcChannel`]):
//! * `m00`, `m20`, `m02`, `m22`: `M⁻¹ = [[a, 0, b], [0, c, 0], [d, 0, 1]]` divided by its middle
//!   entry `c` (Heitz's normalization, which three.js and EEVEE keep): `a/c`,
//!   `d/c`, `b/c`, `1/c` ([`Ltc::heitz_texel`](crate::model::ltc::Ltc::heitz_texel)). A
//!   shader rebuilds `M⁻¹/c = mat3(vec3(m00, 0, m20), vec3(0, 1, 0), vec3(m02, 0, m22))`
//!   (columns), in the frame with the normal +z and the view in the xz-plane at positive x;
//! * `norm`: `∫ f cos`, brdfbake's directional albedo ([`crate::table::albedo`]'s
//!   integrator, the number an `albedo` table holds);
//! * `fresnel`: `∫ (1 − v·h)⁵ f cos`, so that Schlick's Fresnel gives
//!   `F0·norm + (F90 − F0)·fresnel` (the split sum's second term);
//! * `sphere`: the horizon-clipped sphere table ([`clipped_sphere_table`]) at
//!   `z = 2·t_r − 1`, `len = t_v`, where `t_r`, `t_v` are the texel's position in its
//!   roughness and view axes (`(p − lo)/(hi − lo)` of its parameter: `i/(n − 1)` on an
//!   endpoints axis). Heitz's `ltc_2` keeps this table in its 4th channel over the same
//!   texel grid (`fit/fitLTC.cpp`, `genSphereTab`; EEVEE's `ltc_disk_integral` is the same
//!   numbers as a table of its own, the `ltc-sphere` kind); it is not a function of (μ, α)
//!   but of the texture coordinate;
//! * `zero`: 0 (the padding of Heitz's `ltc_2.z`).
//!
//! The matrix channels carry no quadrature error (they are the fit's result, exactly as
//! stored); how well the LTC matches the BRDF is the per-texel fit error, which the bake
//! returns beside the table ([`fit_channels`]) and the sidecar records. The norm and Fresnel
//! channels are integrals with error estimates, gated on the tolerance like every table's.
//!
//! **`ltc-sphere`.** `clipped_sphere_table(z, len)` over the axes `form_factor_z` (the z of
//! the vector form factor's direction, [−1, 1]) and `form_factor_length` ([0, 1]), in closed
//! form (Snyder 1996). EEVEE's `ltc_disk_integral` is this table on the 64² endpoints grid.

use super::spec::{LtcChannel, TableKind, TableSpec};
use super::texel::Misses;
use crate::kernels::ltc_check::{lit_reference_schlick, PolygonLight};
use crate::kernels::ltc_fit::{fit_line, norm_and_fresnel, FitReport, LtcFitOptions, LtcTexel};
use crate::kernels::ltc_polygon::{clipped_sphere_table, ltc_polygon_integral};
use crate::lut::{Axis, Channel};
use crate::model::ltc::Ltc;
use crate::model::{Fresnel, NdfKind};
use rayon::prelude::*;

/// The smallest view cosine an `ltc` table accepts: 10⁻⁴ (θ = 89.994°). The fit's
/// reflected lobe narrows across the plane of incidence as `2μα` and its M⁻¹'s condition
/// grows as `1/(μα)` (`tests/ltc_core.rs`), so at μ → 0 every LTC degenerates; engines stop
/// at θ = 1.57 (μ = 7.96·10⁻⁴, Heitz's `fit/fitLTC.cpp`). A preset reaches grazing views with
/// a clamp (`"clamp": [0.000796, 1]`), as Heitz's layout does.
pub const MIN_VIEW_COSINE: f64 = 1e-4;

/// The smallest α an `ltc` table accepts: 10⁻⁶ (Heitz's tables stop at 10⁻⁵). Below, the
/// LTC of the mirror lobe needs entries beyond the fit's parameter box (`1/(2α)` > 10⁶ in
/// the middle entry's reciprocal), and α = 0 is a mirror, which no LTC holds.
pub const MIN_ALPHA: f64 = 1e-6;

/// What channel `c` holds, for the sidecar and the snippets.
pub fn channel_meaning(c: LtcChannel) -> &'static str {
    match c {
        LtcChannel::M00 => "M^-1[0][0] / M^-1[1][1] (row 0, column 0 of the fitted inverse matrix in Heitz's normalization: a/c)",
        LtcChannel::M20 => "M^-1[2][0] / M^-1[1][1] (row 2, column 0: d/c)",
        LtcChannel::M02 => "M^-1[0][2] / M^-1[1][1] (row 0, column 2: b/c)",
        LtcChannel::M22 => "M^-1[2][2] / M^-1[1][1] (row 2, column 2: 1/c)",
        LtcChannel::Norm => "int f cos dw_l (F = 1): the BRDF's directional albedo, the LTC's magnitude",
        LtcChannel::Fresnel => "int (1 - v.h)^5 f cos dw_l (F = 1): with Schlick's Fresnel the lit value is (F0 * norm + (F90 - F0) * fresnel) * int_P D",
        LtcChannel::Sphere => "the horizon-clipped sphere table at z = 2 t_roughness - 1, len = t_cos_theta_v (t: the texel's position in its axis range, i/(n-1) on an endpoints axis): the clamped cosine's integral over a sphere of form-factor length len and direction z, divided by len",
        LtcChannel::Zero => "0 (padding)",
    }
}

/// The channels of an `ltc` or `ltc-sphere` table.
pub fn channels(spec: &TableSpec) -> Vec<Channel> {
    match spec.kind {
        TableKind::LtcSphere => vec![Channel {
            name: "sphere".into(),
            meaning: "the clamped cosine's integral over a sphere whose vector form factor has length form_factor_length and direction z = form_factor_z, clipped to the horizon, divided by form_factor_length (max(z, 0) at length 0); a shader's clipped form factor is length * this".into(),
        }],
        _ => ltc_channels(spec)
            .iter()
            .map(|&c| Channel {
                name: c.name().into(),
                meaning: channel_meaning(c).into(),
            })
            .collect(),
    }
}

/// The `ltc.channels` of a spec (the default when it lists none).
pub fn ltc_channels(spec: &TableSpec) -> Vec<LtcChannel> {
    spec.ltc_channels
        .clone()
        .unwrap_or_else(|| LtcChannel::DEFAULT.to_vec())
}

/// The channels of the per-texel fit error that an `ltc` table with matrix channels
/// returns beside its texels (in this order): the fit's objective, the paper's L³ error,
/// and the relative error of the probe lights' lit values (rms and largest).
pub fn fit_channels() -> Vec<Channel> {
    vec![
        Channel {
            name: "objective".into(),
            meaning: "the minimized objective: a weighted mean of squared relative residuals of the rule's nodes and the probe lights (sqrt: an rms relative error; kernels/ltc_fit.rs)".into(),
        },
        Channel {
            name: "l3".into(),
            meaning: "int |f cos - norm D|^3 dw / int (f cos)^3 dw over the fit's rule: Heitz et al. 2016's error (the numerator) made relative, comparable across texels".into(),
        },
        Channel {
            name: "lit_rms".into(),
            meaning: "the relative error (X - Y)/(Y + 1e-9 Omega) of the probe lights' lit values (the LTC's X in closed form against the BRDF's Y by quadrature), rms weighted by solid angle".into(),
        },
        Channel {
            name: "lit_max".into(),
            meaning: "the largest |relative error| over the probe lights holding at least 1% of the brightest probe's lit value".into(),
        },
    ]
}

/// The per-texel values of [`fit_channels`].
fn fit_values(f: &FitReport) -> [f64; 4] {
    [f.objective, f.l3_relative, f.lit_rms, f.lit_max]
}

/// Where a texel of `axis` sits in its range: `(p − lo)/(hi − lo)` of its parameter, 0 on
/// an axis of one texel.
pub fn texel_position(axis: &Axis, i: usize) -> f64 {
    let [lo, hi] = axis.range;
    if hi == lo || axis.size < 2 {
        return 0.0;
    }
    ((axis.parameter(i) - lo) / (hi - lo)).clamp(0.0, 1.0)
}

/// The `sphere` channel at positions `t_r` (roughness axis) and `t_v` (view axis).
pub fn sphere_at(t_r: f64, t_v: f64) -> f64 {
    clipped_sphere_table((2.0 * t_r - 1.0).clamp(-1.0, 1.0), t_v.clamp(0.0, 1.0))
        .unwrap_or(f64::NAN)
}

/// The rules of the kinds beyond what `validate.rs` checks of every table: the model, the
/// channels, and the axes' ends.
pub(crate) fn validate(spec: &TableSpec) -> Result<(), String> {
    let m = &spec.model;
    if spec.kind == TableKind::LtcSphere {
        if m.ndf.is_some() || m.diffuse_weight != 0.0 || m.fresnel != Fresnel::None {
            return Err(
                "an ltc-sphere table is a closed form of geometry alone: it takes no model (leave model out)"
                    .into(),
            );
        }
        if spec.ltc_channels.is_some() {
            return Err("ltc.channels applies to ltc tables; an ltc-sphere table has the one channel sphere".into());
        }
        for (ax, [lo, hi]) in spec.axes.iter().zip([[-1.0, 1.0], [0.0, 1.0]]) {
            let [a, b] = ax.range;
            let [c0, c1] = ax.clamp.unwrap_or([lo, hi]);
            if a < lo || b > hi || c0 < lo || c1 > hi {
                return Err(format!(
                    "axes.{}.range and clamp must lie within [{lo}, {hi}] ({}), got range [{a}, {b}]",
                    ax.name,
                    if lo < 0.0 {
                        "the z of a unit direction"
                    } else {
                        "the length of a vector form factor"
                    }
                ));
            }
        }
        return Ok(());
    }
    // ltc
    match (m.ndf, m.diffuse_weight > 0.0) {
        (None, false) => {
            return Err("an ltc table needs a lobe: model.ndf (a specular lobe) or model.diffuse (Lambert)".into())
        }
        (Some(_), true) => {
            return Err(
                "an ltc table fits one lobe: give model.ndf or model.diffuse, not both (one LTC fits a sum of a \
                 specular and a diffuse lobe poorly; bake a table per lobe, the diffuse one is the identity M^-1)"
                    .into(),
            )
        }
        _ => {}
    }
    if m.fresnel != Fresnel::None {
        return Err(format!(
            "model.fresnel must be none for an ltc table: the norm and fresnel channels factor Schlick's Fresnel out \
             (F0 * norm + (F90 - F0) * fresnel), got {:?}",
            m.fresnel.name()
        ));
    }
    let chans = ltc_channels(spec);
    if chans.is_empty() {
        return Err(format!(
            "ltc.channels must list at least one channel (accepted: {})",
            LtcChannel::ALL.map(|c| c.name()).join(", ")
        ));
    }
    for (k, c) in chans.iter().enumerate() {
        if *c != LtcChannel::Zero && chans[..k].contains(c) {
            return Err(format!(
                "ltc.channels[{k}]: {:?} is listed twice (only \"zero\" may repeat)",
                c.name()
            ));
        }
    }
    let view = &spec.axes[0];
    for i in 0..view.size {
        let mu = view.coord(i);
        if !(MIN_VIEW_COSINE..=1.0).contains(&mu) {
            return Err(format!(
                "axes.cos_theta_v: texel {i} is at cosine {}, outside [{MIN_VIEW_COSINE:e}, 1]: an LTC degenerates at \
                 grazing views (its matrix's condition grows as 1/(cos theta_v alpha)); clamp the axis' values \
                 (Heitz's tables: \"clamp\": [0.000796, 1], theta <= 1.57)",
                crate::numfmt::num(mu)
            ));
        }
    }
    let rough = &spec.axes[1];
    for i in 0..rough.size {
        let a = rough.alpha(i).unwrap_or(f64::NAN);
        if a.is_nan() || a < MIN_ALPHA {
            return Err(format!(
                "axes.roughness: texel {i} is at alpha = {}, below the smallest an ltc table accepts ({MIN_ALPHA:e}: \
                 a mirror has no LTC); clamp the axis' values (Heitz's tables: alpha = max(r^2, 1e-5), \
                 \"clamp\": [0.0031623, 1] on a perceptual axis)",
                crate::numfmt::num(a)
            ));
        }
    }
    Ok(())
}

/// What [`bake`] computed: the texels (f32, channels interleaved, μ fastest), per channel
/// the largest error estimate, the evaluations, the first non-finite value, the tolerance
/// misses, and the per-texel fit report ([`fit_channels`], `None` without matrix channels).
pub(crate) struct Baked {
    pub data: Vec<f32>,
    pub max_error: Vec<f64>,
    pub evals: u64,
    pub non_finite: Option<(usize, usize, f64)>,
    pub misses: Misses,
    /// The fit report as f64 values, 4 per texel.
    pub fit: Option<Vec<f64>>,
    /// The first texel whose fit failed: (texel index, message).
    pub failed: Option<(usize, String)>,
    pub stopped: bool,
}

/// The fit's settings for a table: the defaults at the table's tolerance, with the floor
/// relative to the lobe's peak ([`LtcFitOptions::peak_floor`]) at [`PEAK_FLOOR`] for
/// specular lobes other than GGX's.
///
/// Why by NDF: the fit's relative residual `(X − Y)/(Y + εΩ)` asks the LTC to follow the
/// BRDF to the floor ε. An LTC's density falls off away from its axis as a power of the
/// angle (a clamped cosine seen through a linear map), as GGX's does (GGX's NDF is the
/// distribution of normals of an ellipsoid, a linearly stretched hemisphere: Heitz 2018,
/// "Sampling the GGX Distribution of Visible Normals"): there ε = 10⁻⁹ asks nothing an LTC
/// cannot give, and GGX's fit (and every GGX table's bytes) stays as it is. Beckmann's and
/// the Gaussian NDF's tails fall as `exp(−tan²θ/α²)`, Blinn–Phong's as a high power of
/// `cos θ`, and Charlie's sheen lobe is 0 at its centre (`sin^(1/α)θ`): every LTC is
/// orders of magnitude above such a lobe somewhere, each such direction costs `X/(εΩ)`,
/// and with ε = 10⁻⁹ the cheapest LTC was a razor at the parameter box (lit error ~2,
/// `tests/ltc_models.rs`). With the floor at the peak density the residual is the error in
/// units of the peak, `≈ (X − Y)/y_max` away from the peak: an absolute-error fit, as the
/// paper's own objective is (Heitz et al. 2016, §4: `∫|f cos − norm·D|³`).
pub fn fit_options(spec: &TableSpec) -> LtcFitOptions {
    let peak_floor = match spec.model.ndf {
        Some(NdfKind::Ggx) | None => 0.0,
        Some(_) => PEAK_FLOOR,
    };
    LtcFitOptions {
        tolerance: spec.tolerance,
        peak_floor,
        // (sheen scatters back toward the view: `kernels/ltc_fit.rs`, the box's doc)
        retro: spec.model.ndf == Some(NdfKind::Charlie),
        ..Default::default()
    }
}

/// The floor relative to the lobe's peak for lobes an LTC cannot follow relatively
/// ([`fit_options`]): 1, the peak density itself. Measured on `tests/ltc_models.rs`' grid
/// (`examples/ltc_models_check.rs --peak-floor K`, worst texel's lit error `Σ|X − Y|/ΣY`):
/// Beckmann 0.33, 0.254, 0.265, 0.265, 0.268 at K = 10⁻², 0.03, 0.1, 1, 10 (0.75 at 10⁻³,
/// cond·α·μ 2.2; 2.0 at 0, cond·α·μ 8·10⁷); Charlie (Ashikhmin, in its sign box) 0.41,
/// 0.198, 0.202, 0.206 at 10⁻², 0.1, 1, 10 (1.48 at 0, cond·α·μ 1563). 1 is on the plateau
/// for both and says what it does.
pub const PEAK_FLOOR: f64 = 1.0;

/// A roughness line's texels, or the texel where it failed and why.
type LineResult = Result<Vec<LtcTexel>, (usize, String)>;

/// The texels of one roughness line `j` (in μ order), fitted or only integrated.
fn line(
    spec: &TableSpec,
    j: usize,
    fit: bool,
    opts: &LtcFitOptions,
) -> Result<Vec<LtcTexel>, (usize, String)> {
    let view = &spec.axes[0];
    let rough = &spec.axes[1];
    let alpha = rough.alpha(j).expect("roughness axis");
    let brdf = spec.model.brdf(alpha).map_err(|e| (0, e))?;
    if let Some(s) = &brdf.specular {
        s.prepare();
    }
    let mus = view.coords();
    if fit {
        return fit_line(&brdf, &mus, &opts.shape(), opts).map_err(|e| (0, e.to_string()));
    }
    Ok(mus
        .iter()
        .map(|&mu| LtcTexel::unfitted(norm_and_fresnel(&brdf, mu, opts.tolerance)))
        .collect())
}

/// Refits the roughness lines `js` (indices along the roughness axis) of the `ltc` table
/// `spec` (validated) as the bake fits them — the same fixed path, so the same bits — for
/// `verify`: per line, its texels in view order. `None` when `stop()` turned true first
/// (checked before every line); an error names the line.
pub fn refit_lines(
    spec: &TableSpec,
    js: &[usize],
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<Option<Vec<Vec<LtcTexel>>>, String> {
    let opts = fit_options(spec);
    let out: Vec<Option<LineResult>> = js
        .par_iter()
        .with_min_len(1)
        .map(|&j| (!stop()).then(|| line(spec, j, true, &opts)))
        .collect();
    let mut lines = Vec::with_capacity(js.len());
    for (j, l) in js.iter().zip(out) {
        match l {
            None => return Ok(None),
            Some(Ok(t)) => lines.push(t),
            Some(Err((_, msg))) => return Err(format!("refitting roughness texel {j}: {msg}")),
        }
    }
    Ok(Some(lines))
}

/// The values of the kind's channels ([`ltc_channels`] order) that a refit texel gives: the
/// matrix entries; NaN for the others (they are integrals, recomputed by [`exact_at`]).
pub fn refit_matrix_values(spec: &TableSpec, t: &LtcTexel) -> Vec<f64> {
    let h = t.ltc.heitz_texel();
    ltc_channels(spec)
        .iter()
        .map(|c| match c {
            LtcChannel::M00 => h[0],
            LtcChannel::M20 => h[1],
            LtcChannel::M02 => h[2],
            LtcChannel::M22 => h[3],
            _ => f64::NAN,
        })
        .collect()
}

/// The per-texel fit error of a refit texel, in [`fit_channels`]' order.
pub fn refit_fit_values(t: &LtcTexel) -> [f64; 4] {
    fit_values(&t.fit)
}

/// Bakes an `ltc` or `ltc-sphere` table (validated), checking `stop()` before every line
/// (one roughness of an `ltc` table, one row of an `ltc-sphere` table). `limit`: the
/// largest accepted error estimate.
pub(crate) fn bake(spec: &TableSpec, stop: &(dyn Fn() -> bool + Sync), limit: f64) -> Baked {
    if spec.kind == TableKind::LtcSphere {
        return bake_sphere(spec, stop);
    }
    let chans = ltc_channels(spec);
    let nc = chans.len();
    let (nx, ny) = (spec.axes[0].size, spec.axes[1].size);
    let fit = chans.iter().any(|c| c.is_matrix());
    let integrate = fit
        || chans
            .iter()
            .any(|c| matches!(c, LtcChannel::Norm | LtcChannel::Fresnel));
    let opts = fit_options(spec);
    let lines: Vec<Option<LineResult>> = if integrate {
        (0..ny)
            .into_par_iter()
            .with_max_len(1)
            .map(|j| (!stop()).then(|| line(spec, j, fit, &opts)))
            .collect()
    } else {
        Vec::new()
    };
    let mut out = Baked {
        data: Vec::with_capacity(nx * ny * nc),
        max_error: vec![0.0; nc],
        evals: 0,
        non_finite: None,
        misses: Misses::default(),
        fit: fit.then(|| Vec::with_capacity(nx * ny * 4)),
        failed: None,
        stopped: false,
    };
    if integrate && lines.iter().any(Option::is_none) {
        out.stopped = true;
        return out;
    }
    for j in 0..ny {
        let texels = match lines.get(j) {
            Some(Some(Ok(t))) => Some(t),
            Some(Some(Err((_, msg)))) => {
                out.failed = Some((j * nx, msg.clone()));
                return out;
            }
            _ => None,
        };
        for i in 0..nx {
            let t = i + j * nx;
            let tx = texels.map(|v| &v[i]);
            let heitz = tx.map(|x| x.ltc.heitz_texel());
            if let (Some(x), Some(f)) = (tx, out.fit.as_mut()) {
                f.extend(fit_values(&x.fit));
                out.evals += x.evaluations;
            } else if let Some(x) = tx {
                out.evals += x.evaluations;
            }
            for (c, ch) in chans.iter().enumerate() {
                let (v, e) = match ch {
                    LtcChannel::M00 => (heitz.map_or(f64::NAN, |h| h[0]), 0.0),
                    LtcChannel::M20 => (heitz.map_or(f64::NAN, |h| h[1]), 0.0),
                    LtcChannel::M02 => (heitz.map_or(f64::NAN, |h| h[2]), 0.0),
                    LtcChannel::M22 => (heitz.map_or(f64::NAN, |h| h[3]), 0.0),
                    LtcChannel::Norm => tx.map_or((f64::NAN, 0.0), |x| (x.norm, x.norm_error)),
                    LtcChannel::Fresnel => {
                        tx.map_or((f64::NAN, 0.0), |x| (x.fresnel, x.fresnel_error))
                    }
                    LtcChannel::Sphere => (
                        sphere_at(
                            texel_position(&spec.axes[1], j),
                            texel_position(&spec.axes[0], i),
                        ),
                        0.0,
                    ),
                    LtcChannel::Zero => (0.0, 0.0),
                };
                if (!v.is_finite() || !(v as f32).is_finite()) && out.non_finite.is_none() {
                    out.non_finite = Some((t, c, v));
                }
                out.data.push(v as f32);
                out.max_error[c] = out.max_error[c].max(e);
                out.misses.check(limit, t, c, e);
            }
        }
    }
    out
}

/// The `ltc-sphere` table.
fn bake_sphere(spec: &TableSpec, stop: &(dyn Fn() -> bool + Sync)) -> Baked {
    let (az, al) = (&spec.axes[0], &spec.axes[1]);
    let rows: Vec<Option<Vec<f64>>> = (0..al.size)
        .into_par_iter()
        .map(|j| {
            if stop() {
                return None;
            }
            let len = al.coord(j).clamp(0.0, 1.0);
            Some(
                (0..az.size)
                    .map(|i| {
                        clipped_sphere_table(az.coord(i).clamp(-1.0, 1.0), len).unwrap_or(f64::NAN)
                    })
                    .collect(),
            )
        })
        .collect();
    let mut out = Baked {
        data: Vec::with_capacity(az.size * al.size),
        max_error: vec![0.0],
        evals: 0,
        non_finite: None,
        misses: Misses::default(),
        fit: None,
        failed: None,
        stopped: rows.iter().any(Option::is_none),
    };
    for (t, v) in rows.into_iter().flatten().flatten().enumerate() {
        if !v.is_finite() && out.non_finite.is_none() {
            out.non_finite = Some((t, 0, v));
        }
        out.data.push(v as f32);
    }
    out
}

/// The view cosine and α an `ltc` table's texels hold at the physical coordinates `x` (in
/// the kind's order; each axis' clamp applied), or why the table is not defined there.
pub fn view_and_alpha(spec: &TableSpec, x: &[f64]) -> Result<(f64, f64), String> {
    if x.len() != 2 || spec.axes.len() != 2 {
        return Err(format!(
            "{} coordinates for {} axes",
            x.len(),
            spec.axes.len()
        ));
    }
    let p = [spec.axes[0].clamped(x[0]), spec.axes[1].clamped(x[1])];
    let mu = p[0];
    let alpha = match spec.axes[1].quantity {
        crate::lut::Quantity::Roughness(q) => q.to_alpha(p[1]),
        _ => f64::NAN,
    };
    if !(MIN_VIEW_COSINE..=1.0).contains(&mu) {
        return Err(format!(
            "no exact value there: cos_theta_v = {} is outside [{MIN_VIEW_COSINE:e}, 1], where an ltc table is defined",
            crate::numfmt::num(mu)
        ));
    }
    if alpha.is_nan() || alpha < MIN_ALPHA {
        return Err(format!(
            "no exact value there: alpha = {} is below {MIN_ALPHA:e}, where an ltc table is defined",
            crate::numfmt::num(alpha)
        ));
    }
    Ok((mu, alpha))
}

/// The lit value of one polygon light at a point of an `ltc` table, as a shader gets it
/// from the table and as it is ([`lit_probe`]).
#[derive(Clone, Debug)]
pub struct LitProbe {
    /// The point: view cosine and α (each axis' clamp applied).
    pub mu: f64,
    pub alpha: f64,
    /// The LTC rebuilt from the looked-up matrix channels.
    pub ltc: Ltc,
    /// `∫_P D` of that LTC over the light ([`ltc_polygon_integral`], clipped as a shader clips).
    pub form_factor: f64,
    /// The norm used: the table's (looked up) or, `norm_computed`, brdfbake's albedo.
    pub norm: f64,
    pub norm_computed: bool,
    /// The Fresnel channel used with `f0` (the table's, or computed: `fresnel_computed`).
    pub fresnel: Option<f64>,
    pub fresnel_computed: bool,
    /// Schlick's F0 (F90 = 1), `None` for F = 1.
    pub f0: Option<f64>,
    /// `norm`, or `F0·norm + (1 − F0)·fresnel`.
    pub magnitude: f64,
    /// The table's lit value, `magnitude·form_factor`.
    pub table: f64,
    /// The exact value: `∫_P F f cos` by quadrature ([`lit_reference_schlick`]), with its
    /// error estimate.
    pub exact: f64,
    pub exact_error: f64,
    /// `(table − exact)/exact`.
    pub relative_error: f64,
}

/// The lit value of `light` at the point `x` (in the kind's order) of the `ltc` table
/// `spec`, from `looked_up` (the kind's computed channels, [`ltc_channels`] order, as a
/// lookup there gives them: `None` where the texture holds no such channel): `M⁻¹` rebuilt
/// from `m00, m20, m02, m22` ([`Ltc::from_heitz_texel`]), `∫_P D` in closed form, times the
/// norm (with `f0`, Schlick's `F0·norm + (1 − F0)·fresnel`), next to the BRDF's own lit value
/// by quadrature to relative `rel_tol`. A norm or Fresnel channel the table does not hold
/// (Heitz's layout keeps them in a second texture) is brdfbake's integral at the point,
/// which the table's would hold.
pub fn lit_probe(
    spec: &TableSpec,
    x: &[f64],
    looked_up: &[Option<f64>],
    light: &PolygonLight,
    f0: Option<f64>,
    rel_tol: f64,
) -> Result<LitProbe, String> {
    let chans = ltc_channels(spec);
    let get = |c: LtcChannel| {
        chans
            .iter()
            .position(|&k| k == c)
            .and_then(|i| looked_up.get(i).copied().flatten())
    };
    let m = [
        LtcChannel::M00,
        LtcChannel::M20,
        LtcChannel::M02,
        LtcChannel::M22,
    ]
    .map(get);
    let [Some(m00), Some(m20), Some(m02), Some(m22)] = m else {
        return Err(
            "the table holds no matrix channels (m00, m20, m02, m22): probe the texture that does              (Heitz's layout: ltc_1) for a lit value"
                .into(),
        );
    };
    let (mu, alpha) = view_and_alpha(spec, x)?;
    let ltc = Ltc::from_heitz_texel([m00, m20, m02, m22])
        .map_err(|e| format!("the looked-up matrix is no LTC: {e}"))?;
    let form_factor = ltc_polygon_integral(&ltc, &light.verts).map_err(|e| e.to_string())?;
    let brdf = spec.model.brdf(alpha)?;
    if let Some(s) = &brdf.specular {
        s.prepare();
    }
    let (mut norm, mut fresnel) = (get(LtcChannel::Norm), get(LtcChannel::Fresnel));
    let (norm_computed, fresnel_computed) = (norm.is_none(), f0.is_some() && fresnel.is_none());
    if norm_computed || fresnel_computed {
        let nf = norm_and_fresnel(&brdf, mu, rel_tol);
        norm = norm.or(Some(nf.norm));
        fresnel = fresnel.or(Some(nf.fresnel));
    }
    let norm = norm.expect("set");
    let magnitude = match (f0, fresnel) {
        (Some(f0), Some(fr)) => f0 * norm + (1.0 - f0) * fr,
        _ => norm,
    };
    let table = magnitude * form_factor;
    let r = lit_reference_schlick(&brdf, alpha, mu, light, f0, rel_tol)
        .map_err(|e| format!("the exact value: {e}"))?;
    Ok(LitProbe {
        mu,
        alpha,
        ltc,
        form_factor,
        norm,
        norm_computed,
        fresnel: f0.and(fresnel),
        fresnel_computed,
        f0,
        magnitude,
        table,
        exact: r.value,
        exact_error: r.error,
        relative_error: (table - r.value) / r.value,
    })
}

/// The exact value of every channel of an `ltc` or `ltc-sphere` table at the physical
/// coordinates `x` (one per axis, in the kind's order), at tolerance `tol`, with error
/// estimates: the norm and Fresnel channels by their integrals, the sphere table in closed
/// form at the point's position in the texture, `zero` 0. A matrix entry has no exact value
/// (the LTC is a fit, and a fit warm-started along a path is defined at the texels only):
/// NaN, which `probe` and `verify` treat as such (they measure the lit value, and refit).
pub fn exact_at(spec: &TableSpec, x: &[f64], tol: f64) -> Result<(Vec<f64>, Vec<f64>), String> {
    if x.len() != spec.axes.len() {
        return Err(format!(
            "{} coordinates for {} axes",
            x.len(),
            spec.axes.len()
        ));
    }
    if spec.kind == TableKind::LtcSphere {
        let p = [spec.axes[0].clamped(x[0]), spec.axes[1].clamped(x[1])];
        let v = clipped_sphere_table(p[0].clamp(-1.0, 1.0), p[1].clamp(0.0, 1.0))
            .map_err(|e| format!("no exact value there: {e}"))?;
        return Ok((vec![v], vec![0.0]));
    }
    let (mu, alpha) = view_and_alpha(spec, x)?;
    let chans = ltc_channels(spec);
    let nf = if chans
        .iter()
        .any(|c| matches!(c, LtcChannel::Norm | LtcChannel::Fresnel))
    {
        let brdf = spec
            .model
            .brdf(alpha)
            .map_err(|e| format!("no exact value there: {e}"))?;
        if let Some(s) = &brdf.specular {
            s.prepare();
        }
        Some(norm_and_fresnel(&brdf, mu, tol))
    } else {
        None
    };
    let mut v = Vec::with_capacity(chans.len());
    let mut e = Vec::with_capacity(chans.len());
    for c in &chans {
        let (a, b) = match c {
            LtcChannel::Norm => nf.map_or((f64::NAN, 0.0), |n| (n.norm, n.norm_error)),
            LtcChannel::Fresnel => nf.map_or((f64::NAN, 0.0), |n| (n.fresnel, n.fresnel_error)),
            LtcChannel::Sphere => (
                sphere_at(spec.axes[1].normalized(x[1]), spec.axes[0].normalized(x[0])),
                0.0,
            ),
            LtcChannel::Zero => (0.0, 0.0),
            _ => (f64::NAN, 0.0),
        };
        v.push(a);
        e.push(b);
    }
    Ok((v, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_channel_follows_the_texture_position() {
        // the corners of Heitz's grid: z = -1 (nothing above the horizon) and z = 1
        assert_eq!(sphere_at(0.0, 0.0), 0.0);
        assert_eq!(sphere_at(1.0, 0.0), 1.0);
        assert!((sphere_at(1.0, 1.0) - 1.0).abs() < 1e-12);
        // len = 0: the limit max(z, 0)
        assert!((sphere_at(0.75, 0.0) - 0.5).abs() < 1e-15);
    }
}
