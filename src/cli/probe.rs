//! `brdfbake probe FILE --at name=value,...`: what a GPU reads vs the exact value.

use super::CliError;
use crate::lut::Filter;
use serde_json::json;
use std::path::PathBuf;

/// Tolerance of the exact reference computation.
pub const EXACT_TOLERANCE: f64 = 1e-10;

#[derive(clap::Args, Debug)]
pub struct ProbeArgs {
    /// A .exr or .ktx2 texture brdfbake wrote, with its .json sidecar next to it (or the sidecar).
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
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
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
            "{}: no texture found next to the sidecar (its files.exr / files.ktx2)",
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
            "note: \"-\": no exact value at this point: an LTC matrix entry is the fit at each texel, not a function to evaluate between them (verify refits texels; the lit error of the fit is in the sidecar's ltc section)"
        );
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
