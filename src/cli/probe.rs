//! `brdfbake probe FILE --at name=value,...`: what a GPU reads vs the exact value.

use super::CliError;
use crate::lut::Filter;
use serde_json::json;
use std::path::PathBuf;

/// Tolerance of the exact reference computation.
pub const EXACT_TOLERANCE: f64 = 1e-10;
/// Relative tolerance the exact lit value of an ltc table's polygon light aims at (a 2D
/// adaptive quadrature: 1e-9 keeps it to ~1 s on a narrow lobe, far below any fit's error);
/// where the quadrature's own estimate is larger, probe prints it and says so.
pub const LIT_TOLERANCE: f64 = 1e-9;

#[derive(clap::Args, Debug)]
pub struct ProbeArgs {
    /// A .exr, .ktx2 or .dds texture brdfbake wrote, with its .json sidecar next to it (or the sidecar).
    pub file: PathBuf,
    /// Where to sample, one value per axis in the axis' own quantity (e.g.
    /// cos_theta_v=0.5,roughness=0.3; the names are the sidecar's axis names).
    #[arg(long, value_name = "NAME=VALUE,...")]
    pub at: String,
    /// How the GPU weights the texels: `ideal` (exact weights, as CPUs and software
    /// rasterizers filter) or `hardware` (weights rounded to multiples of 1/256, as GPUs
    /// with 8 bits of sub-texel precision filter: the value such a GPU reads).
    #[arg(long, value_enum, default_value_t = FilterArg::Ideal)]
    pub filter: FilterArg,
    /// For an ltc table: the polygon light whose lit value is shown from the table and
    /// exactly, as 3 to 8 vertices `x,y,z` separated by spaces: positions relative to the
    /// shading point in the frame with the normal +z and the view in the xz-plane at +x
    /// (the mirror direction is at -x), convex as seen from the point, either winding.
    /// Default: a square of side 1 at distance 2 facing the point, centred on the mirror
    /// direction (lifted to 10° above the horizon at grazing views).
    #[arg(long, value_name = "X,Y,Z X,Y,Z X,Y,Z ...", allow_hyphen_values = true)]
    pub polygon: Option<String>,
    /// For an ltc table: Schlick's F0 of the lit value (F90 = 1: the table's
    /// F0 * norm + (1 - F0) * fresnel against the BRDF with that Fresnel); without it F = 1.
    #[arg(long, value_name = "F0")]
    pub f0: Option<f64>,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

/// What `--polygon` accepts, for its errors.
const POLYGON_ACCEPTED: &str = "3 to 8 vertices x,y,z separated by spaces, positions relative to the shading point (normal +z, view in the xz-plane at +x), convex as seen from it, e.g. --polygon \"-0.5,-0.5,1 0.5,-0.5,1 0.5,0.5,1 -0.5,0.5,1\"";

/// Parses and checks `--polygon` ([`crate::kernels::ltc_check::polygon_light`]).
pub(super) fn parse_polygon(
    s: &str,
) -> Result<(crate::kernels::ltc_check::PolygonLight, bool), CliError> {
    let mut verts = Vec::new();
    for (k, part) in s
        .split(|c: char| c.is_whitespace() || c == ';')
        .filter(|p| !p.is_empty())
        .enumerate()
    {
        let nums: Vec<Option<f64>> = part.split(',').map(|t| t.trim().parse().ok()).collect();
        match nums[..] {
            [Some(x), Some(y), Some(z)] => verts.push([x, y, z]),
            _ => {
                return Err(CliError::input(format!(
                    "--polygon: vertex {} {part:?} is not x,y,z (three numbers separated by commas); accepted: {POLYGON_ACCEPTED}",
                    k + 1
                )))
            }
        }
    }
    crate::kernels::ltc_check::polygon_light(&verts)
        .map_err(|e| CliError::input(format!("--polygon: {e}; accepted: {POLYGON_ACCEPTED}")))
}

/// A polygon's vertices as `--polygon` spells them.
fn polygon_text(verts: &[[f64; 3]]) -> String {
    verts
        .iter()
        .map(|p| format!("{},{},{}", short(p[0]), short(p[1]), short(p[2])))
        .collect::<Vec<_>>()
        .join(" ")
}

/// A coordinate with 9 significant digits, trailing zeros dropped.
fn short(x: f64) -> String {
    let v: f64 = format!("{x:.8e}").parse().unwrap_or(x);
    let v = if v == 0.0 { 0.0 } else { v };
    format!("{v}")
}

/// `--filter`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum FilterArg {
    Ideal,
    Hardware,
}

/// Parses `a=1,b=2` against the axis names; every axis exactly once.
pub(super) fn parse_at(s: &str, names: &[&str]) -> Result<Vec<f64>, CliError> {
    let accepted = names.join(", ");
    let mut out = vec![None; names.len()];
    for part in s.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (k, v) = part.split_once('=').ok_or_else(|| {
            CliError::input(format!(
                "--at: {part:?} is not NAME=VALUE (axes of this table: {accepted})"
            ))
        })?;
        let k = k.trim();
        let i = names.iter().position(|n| *n == k).ok_or_else(|| {
            CliError::input(format!(
                "--at: unknown axis {k:?} (axes of this table: {accepted})"
            ))
        })?;
        let x: f64 = v
            .trim()
            .parse()
            .ok()
            .filter(|x: &f64| x.is_finite())
            .ok_or_else(|| CliError::input(format!("--at: {k}={v:?} is not a finite number")))?;
        if out[i].replace(x).is_some() {
            return Err(CliError::input(format!("--at: axis {k} is given twice")));
        }
    }
    let missing: Vec<&str> = names
        .iter()
        .zip(&out)
        .filter(|(_, v)| v.is_none())
        .map(|(n, _)| *n)
        .collect();
    if !missing.is_empty() {
        return Err(CliError::input(format!(
            "--at: missing {} (axes of this table: {accepted})",
            missing.join(", ")
        )));
    }
    Ok(out.into_iter().map(|v| v.expect("checked")).collect())
}

pub fn run(a: ProbeArgs) -> Result<(), CliError> {
    // (the exact value is one integral, bounded by the integral budget: ~2 s at most)
    let deadline = super::inspect::admit_read(&a.guards, "this probe", &a.file)?;
    let rb = super::inspect::read(&a.file)?;
    let table = rb.table.as_ref().ok_or_else(|| {
        if rb.sidecar.is_some() {
            return CliError::input(format!(
                "{}: a table of `measured --out` (kind {}): there is no exact value to probe against \
                 (the data are measured); `inspect` shows it",
                a.file.display(),
                crate::meta::MEASURED_TABLE_KIND
            ));
        }
        CliError::input(format!(
            "{}: probe needs the JSON sidecar next to the texture (it says what the axes are)",
            a.file.display()
        ))
    })?;
    let lut = rb.lut.as_ref().ok_or_else(|| {
        CliError::input(format!(
            "{}: no texture found next to the sidecar (its files.exr / files.ktx2 / files.dds)",
            a.file.display()
        ))
    })?;
    let names: Vec<&str> = lut.axes.iter().map(|x| x.name.as_str()).collect();
    let mut notes = Vec::new();
    if rb.hash_matches == Some(false) {
        notes.push(
            "the sidecar's input_hash does not match the table it describes (edited, or written by another brdfbake version): the exact values follow the sidecar as it is now".to_string(),
        );
    }
    let x = parse_at(&a.at, &names)?;
    let is_ltc = table.spec.kind == crate::table::TableKind::Ltc;
    for (flag, given) in [("--polygon", a.polygon.is_some()), ("--f0", a.f0.is_some())] {
        if given && !is_ltc {
            return Err(CliError::input(format!(
                "{flag} applies to ltc tables (the lit value of a polygon light); {} is a {} table",
                a.file.display(),
                table.spec.kind.name()
            )));
        }
    }
    if let Some(f0) = a.f0 {
        if !(0.0..=1.0).contains(&f0) {
            return Err(CliError::input(format!(
                "--f0 must be a number in [0, 1] (Schlick's reflectance at normal incidence), got {f0}"
            )));
        }
    }
    let user_light = a.polygon.as_deref().map(parse_polygon).transpose()?;
    let unscale = |v: Vec<f64>| -> Vec<f64> { v.iter().map(|v| v / rb.scale).collect() };
    let ideal = unscale(lut.lookup(&x));
    let hw_axes = table.hardware_filtered_axes();
    let gpu = match a.filter {
        FilterArg::Ideal => ideal.clone(),
        FilterArg::Hardware => unscale(lut.lookup_filtered(&x, Filter::Hardware { axes: hw_axes })),
    };
    let bound = unscale(lut.weight_rounding_bound(hw_axes));
    // beyond the edge texels the GPU reads the edge texel (clamp-to-edge): where the exact
    // value has no meaning at `x` (a cosine above 1), it is given where the GPU reads
    let mut exact_x = x.clone();
    let (computed, computed_err) = match crate::readback::exact_at(
        &table.spec,
        &table.to_kind_order(&x),
        EXACT_TOLERANCE,
    ) {
        Ok(r) => r,
        Err(e) => {
            for (v, ax) in exact_x.iter_mut().zip(&lut.axes) {
                let (first, last) = (ax.coord(0), ax.coord(ax.size - 1));
                *v = v.clamp(first.min(last), first.max(last));
            }
            if exact_x == x {
                return Err(CliError::input(format!("--at {}: {e}", a.at)));
            }
            let r = crate::readback::exact_at(
                &table.spec,
                &table.to_kind_order(&exact_x),
                EXACT_TOLERANCE,
            )
            .map_err(|e| CliError::input(format!("--at {}: {e}", a.at)))?;
            notes.push(format!(
                "{e} at the given point: the exact value is given where the GPU reads, at the edge texels' coordinates ({})",
                names
                    .iter()
                    .zip(&exact_x)
                    .map(|(n, v)| format!("{n}={v}"))
                    .collect::<Vec<_>>()
                    .join(",")
            ));
            r
        }
    };
    // the stored channels' exact values (the preset's `channels`: 1 - E, constants, ...)
    let (exact, err) = (
        table.stored_values(&computed),
        table.stored_errors(&computed_err),
    );
    if deadline.passed() {
        return Err(super::guards::stopped("this probe", &deadline));
    }
    // an ltc table with its matrix: the lit value of a polygon light, from the looked-up
    // texels and exactly
    let kind_x = table.to_kind_order(&exact_x);
    let chans = crate::table::ltc::ltc_channels(&table.spec);
    let looked_up = table.computed_from_stored(&gpu, chans.len());
    let has_matrix = is_ltc
        && chans
            .iter()
            .zip(&looked_up)
            .filter(|(c, v)| c.is_matrix() && v.is_some())
            .count()
            == 4;
    let lit = if has_matrix {
        let (light, reversed) = match user_light {
            Some(l) => l,
            None => {
                let (mu, _) = crate::table::ltc::view_and_alpha(&table.spec, &kind_x)
                    .map_err(|e| CliError::input(format!("--at {}: {e}", a.at)))?;
                parse_polygon(&polygon_text(
                    &crate::kernels::ltc_check::default_test_quad(mu),
                ))?
            }
        };
        if reversed {
            notes.push("--polygon is wound clockwise as seen from the shading point: the light is taken as two-sided (its vertices reversed)".into());
        }
        let r = crate::deadline::scoped(&deadline, || {
            crate::table::ltc::lit_probe(
                &table.spec,
                &kind_x,
                &looked_up,
                &light,
                a.f0,
                LIT_TOLERANCE,
            )
        });
        if deadline.passed() {
            return Err(super::guards::stopped("this probe", &deadline));
        }
        let r = r.map_err(|e| CliError::input(format!("--at {}: the lit value: {e}", a.at)))?;
        // the quadrature aims at LIT_TOLERANCE relative; where its own estimate says it got
        // less, the figure printed is the one that holds
        if r.exact_error > LIT_TOLERANCE * r.exact.abs() {
            notes.push(format!(
                "the exact lit value's error estimate {} is {} relative, above the {} the quadrature aims for (its evaluation budget ran out on this light): the exact value holds to that estimate, and the relative error to about {}",
                crate::numfmt::short(r.exact_error),
                crate::numfmt::short(r.exact_error / r.exact.abs().max(f64::MIN_POSITIVE)),
                crate::numfmt::num(LIT_TOLERANCE),
                crate::numfmt::short(r.exact_error / r.exact.abs().max(f64::MIN_POSITIVE))
            ));
        }
        if r.norm_computed {
            notes.push("the table holds no norm channel (Heitz's layout keeps it in ltc_2): the lit value uses brdfbake's albedo at the point, which that channel holds".into());
        }
        if r.fresnel_computed {
            notes.push("the table holds no fresnel channel: the lit value uses brdfbake's integral at the point, which that channel holds".into());
        }
        Some((light, r))
    } else {
        if user_light.is_some() {
            return Err(CliError::input(format!(
                "--polygon: {} holds no matrix channels (m00, m20, m02, m22): probe the texture that does (Heitz's layout: ltc_1) for a lit value",
                a.file.display()
            )));
        }
        None
    };
    if deadline.passed() {
        return Err(super::guards::stopped("this probe", &deadline));
    }
    let filtered: Vec<&str> = lut.axes[..hw_axes]
        .iter()
        .map(|ax| ax.name.as_str())
        .collect();
    if a.filter == FilterArg::Hardware {
        notes.push(format!(
            "hardware filtering: the weights along {} are rounded to multiples of 1/256 (8-bit sub-texel precision){}; anywhere in this table that moves a lookup by at most {} per channel",
            filtered.join(", "),
            if hw_axes < lut.axes.len() { "; the 2D-array layout blends the slices in the shader, exactly" } else { "" },
            bound.iter().map(|b| format!("{b:.3e}")).collect::<Vec<_>>().join(", ")
        ));
    }
    notes.extend(
        lut.axes
            .iter()
            .zip(&x)
            .filter(|(ax, v)| {
                let [lo, hi] = ax.coordinate_span();
                **v < lo || **v > hi
            })
            .map(|(ax, v)| {
                let [lo, hi] = ax.coordinate_span();
                format!(
                    "{}={v} lies outside the axis range [{lo}, {hi}]: the GPU clamps to the edge",
                    ax.name
                )
            }),
    );
    if a.json {
        let ch: Vec<_> = lut
            .channels
            .iter()
            .enumerate()
            .map(|(c, ch)| {
                let mut v = json!({"channel": ch.name, "gpu": gpu[c], "exact": exact[c], "exact_error_estimate": err[c], "difference": gpu[c] - exact[c]});
                if a.filter == FilterArg::Hardware {
                    v["gpu_ideal"] = json!(ideal[c]);
                    v["weight_rounding"] = json!(gpu[c] - ideal[c]);
                    v["weight_rounding_bound"] = json!(bound[c]);
                }
                v
            })
            .collect();
        let point = |p: &[f64]| -> serde_json::Map<String, serde_json::Value> {
            names
                .iter()
                .zip(p)
                .map(|(n, v)| (n.to_string(), json!(v)))
                .collect()
        };
        let mut doc = json!({
            "file": a.file.display().to_string(),
            "filter": match a.filter { FilterArg::Ideal => "ideal", FilterArg::Hardware => "hardware" },
            "at": point(&x),
            "texture_coordinates": lut.axes.iter().zip(&x).map(|(ax, v)| ax.texture_coordinate(*v)).collect::<Vec<_>>(),
            "channels": ch,
            "notes": notes,
        });
        if exact_x != x {
            doc["exact_at"] = json!(point(&exact_x));
        }
        if let Some((light, r)) = &lit {
            doc["lit"] = json!({
                "polygon": light.verts,
                "polygon_default": a.polygon.is_none(),
                "crosses_horizon": light.crosses_horizon,
                "cos_theta_v": r.mu,
                "alpha": r.alpha,
                "f0": r.f0,
                "inverse_matrix": r.ltc.inverse_matrix(),
                "form_factor": r.form_factor,
                "norm": r.norm,
                "norm_from": if r.norm_computed { "computed" } else { "table" },
                "fresnel": r.fresnel,
                "table": r.table,
                "exact": r.exact,
                "exact_error_estimate": r.exact_error,
                "relative_error": r.relative_error,
                "meaning": "table: (F0 * norm + (1 - F0) * fresnel, or norm without f0) * the LTC's integral over the polygon (M^-1 rebuilt from the looked-up matrix channels, clipped to the horizon as a shader does); exact: the BRDF (with Schlick's Fresnel for f0) times cos integrated over the polygon clipped to the horizon, by adaptive quadrature; relative_error = (table - exact) / exact; inverse_matrix: the rebuilt M^-1 (rows [[a, 0, b], [0, c, 0], [d, 0, 1]]: the looked-up channels times c = 1/m22); polygon: the light's vertices, counterclockwise about the direction away from the shading point (a clockwise --polygon is reversed: the light is two-sided)",
            });
        }
        if a.filter == FilterArg::Hardware {
            doc["hardware_filtered_axes"] = json!(filtered);
        }
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
        return Ok(());
    }
    let tc: Vec<String> = lut
        .axes
        .iter()
        .zip(&x)
        .map(|(ax, v)| format!("{:.9}", ax.texture_coordinate(*v)))
        .collect();
    outln!("texture coordinates (u, v, w): ({})", tc.join(", "));
    outln!(
        "{:<12} {:>20} {:>20} {:>12}",
        "channel",
        match a.filter {
            FilterArg::Ideal => "GPU (filtered)",
            FilterArg::Hardware => "GPU (8-bit weights)",
        },
        "exact",
        "difference"
    );
    for (c, ch) in lut.channels.iter().enumerate() {
        if exact[c].is_nan() {
            // (a channel with no exact value between texels: an LTC fit's matrix entry)
            outln!("{:<12} {:>20.12} {:>20} {:>12}", ch.name, gpu[c], "-", "-");
            continue;
        }
        outln!(
            "{:<12} {:>20.12} {:>20.12} {:>12.3e}",
            ch.name,
            gpu[c],
            exact[c],
            gpu[c] - exact[c]
        );
    }
    if exact.iter().any(|v| v.is_nan()) {
        outln!(
            "note: \"-\": no exact value at this point: an LTC matrix entry is the fit at each texel, not a function to evaluate between them; what it is for is the lit value below (verify refits texels; the fit's error is in the sidecar's ltc section)"
        );
    }
    if let Some((light, r)) = &lit {
        outln!(
            "lit value of the polygon {}{} at cos_theta_v={}, alpha={} ({}):",
            polygon_text(&light.verts),
            if a.polygon.is_none() {
                " (the default: a square of side 1 at distance 2, centred on the mirror direction)"
            } else {
                ""
            },
            short(r.mu),
            short(r.alpha),
            match r.f0 {
                Some(f0) => format!("Schlick's Fresnel, F0 = {f0}, F90 = 1"),
                None => "F = 1".into(),
            }
        );
        outln!(
            "  table          {:>20.12}  = {} {:.9} x LTC integral {:.9}",
            r.table,
            if r.f0.is_some() {
                "F0 norm + (1 - F0) fresnel"
            } else {
                "norm"
            },
            r.magnitude,
            r.form_factor
        );
        outln!(
            "  exact          {:>20.12}  (quadrature of BRDF x cos over the polygon, error estimate {:.1e})",
            r.exact,
            r.exact_error
        );
        outln!("  relative error {:>20.3e}", r.relative_error);
    }
    if a.filter == FilterArg::Hardware {
        let v: Vec<String> = lut
            .channels
            .iter()
            .zip(&ideal)
            .map(|(ch, v)| format!("{} {v:.12}", ch.name))
            .collect();
        outln!("ideal filtering (exact weights): {}", v.join(", "));
    }
    for n in notes {
        outln!("note: {n}");
    }
    Ok(())
}
