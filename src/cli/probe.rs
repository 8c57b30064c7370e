//! `brdfbake probe FILE --at name=value,...`: what a GPU reads vs the exact value.

use super::CliError;
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
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
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
    let gpu: Vec<f64> = lut.lookup(&x).iter().map(|v| v / rb.scale).collect();
    let (exact, err) = crate::readback::exact_at(&table.spec, &x, EXACT_TOLERANCE)
        .map_err(|e| CliError::input(format!("--at {}: {e}", a.at)))?;
    if deadline.passed() {
        return Err(super::guards::stopped("this probe", &deadline));
    }
    notes.extend(
        lut.axes
            .iter()
            .zip(&x)
            .filter(|(ax, v)| **v < ax.range[0] || **v > ax.range[1])
            .map(|(ax, v)| {
                format!(
                    "{}={v} lies outside the axis range [{}, {}]: the GPU clamps to the edge",
                    ax.name, ax.range[0], ax.range[1]
                )
            }),
    );
    if a.json {
        let ch: Vec<_> = lut
            .channels
            .iter()
            .enumerate()
            .map(|(c, ch)| {
                json!({"channel": ch.name, "gpu": gpu[c], "exact": exact[c], "exact_error_estimate": err[c], "difference": gpu[c] - exact[c]})
            })
            .collect();
        let doc = json!({
            "file": a.file.display().to_string(),
            "at": names.iter().zip(&x).map(|(n, v)| (n.to_string(), json!(v))).collect::<serde_json::Map<_, _>>(),
            "texture_coordinates": lut.axes.iter().zip(&x).map(|(ax, v)| ax.texture_coordinate(*v)).collect::<Vec<_>>(),
            "channels": ch,
            "notes": notes,
        });
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
        "GPU (filtered)",
        "exact",
        "difference"
    );
    for (c, ch) in lut.channels.iter().enumerate() {
        outln!(
            "{:<12} {:>20.12} {:>20.12} {:>12.3e}",
            ch.name,
            gpu[c],
            exact[c],
            gpu[c] - exact[c]
        );
    }
    for n in notes {
        outln!("note: {n}");
    }
    Ok(())
}
