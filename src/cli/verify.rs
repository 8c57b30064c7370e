//! `brdfbake verify PRESET|FILE`: recompute a spread of texels at high accuracy and gate on
//! the max error per channel.

use super::CliError;
use crate::lut::Lut;
use crate::table::TableSpec;
use rayon::prelude::*;
use serde_json::json;
use std::collections::BTreeSet;
use std::path::Path;

/// Tolerance of the reference recomputation.
pub const REFERENCE_TOLERANCE: f64 = 1e-10;
/// Number of pseudo-random texels checked besides corners, edge midpoints and the centre.
pub const RANDOM_SAMPLES: usize = 64;

#[derive(clap::Args, Debug)]
pub struct VerifyArgs {
    /// A preset (name or file; baked in memory) or a .exr/.ktx2/.json file brdfbake wrote.
    pub target: String,
    /// Largest accepted error per channel: absolute, relative for |values| > 1.
    #[arg(long, default_value_t = 1e-6)]
    pub tolerance: f64,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
}

/// The texels checked: every combination of {first, middle, last} per axis, and
/// [`RANDOM_SAMPLES`] more from a fixed-seed generator.
pub fn sample_texels(lut: &Lut) -> Vec<[usize; 3]> {
    let dims = [lut.dim(0), lut.dim(1), lut.dim(2)];
    let mut set = BTreeSet::new();
    let picks = |n: usize| [0, n / 2, n - 1];
    for x in picks(dims[0]) {
        for y in picks(dims[1]) {
            for z in picks(dims[2]) {
                set.insert([x, y, z]);
            }
        }
    }
    let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = |n: usize| {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 33) % n as u64) as usize
    };
    for _ in 0..RANDOM_SAMPLES {
        set.insert([next(dims[0]), next(dims[1]), next(dims[2])]);
    }
    set.into_iter().collect()
}

/// Per channel: (max error, texel where it occurs, stored, exact).
pub type ChannelError = (f64, [usize; 3], f64, f64);

/// Compares sampled texels of `lut` (stored values divided by `scale`) with the values
/// recomputed from `spec` at [`REFERENCE_TOLERANCE`].
pub fn verify_lut(
    spec: &TableSpec,
    lut: &Lut,
    scale: f64,
) -> Result<(usize, Vec<ChannelError>), String> {
    let texels = sample_texels(lut);
    let exact: Vec<Result<Vec<f64>, String>> = texels
        .par_iter()
        .map(|idx| {
            let x: Vec<f64> = lut
                .axes
                .iter()
                .enumerate()
                .map(|(k, a)| a.coord(idx[k]))
                .collect();
            crate::readback::exact_at(spec, &x, REFERENCE_TOLERANCE).map(|r| r.0)
        })
        .collect();
    let nc = lut.channels.len();
    let mut out = vec![(0.0, [0; 3], 0.0, 0.0); nc];
    for (idx, ex) in texels.iter().zip(exact) {
        let ex = ex?;
        for c in 0..nc {
            let stored = lut.texel(*idx, c) as f64 / scale;
            let d = (stored - ex[c]).abs() / ex[c].abs().max(1.0);
            if d > out[c].0 || d.is_nan() {
                out[c] = (d, *idx, stored, ex[c]);
            }
        }
    }
    Ok((texels.len(), out))
}

pub fn run(a: VerifyArgs) -> Result<(), CliError> {
    if !(a.tolerance.is_finite() && a.tolerance > 0.0) {
        return Err(CliError::input(format!(
            "--tolerance must be a positive number, got {}",
            a.tolerance
        )));
    }
    let p = Path::new(&a.target);
    let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("");
    let mut jobs: Vec<(String, TableSpec, Lut, f64)> = Vec::new();
    let schema = if ext == "json" { json_schema(p) } else { None };
    if let Some(sc) = schema.as_deref() {
        if sc != crate::meta::SCHEMA && sc.starts_with("brdfbake.lut") {
            return Err(CliError::input(format!(
                "{}: sidecar schema {sc:?} is not one this brdfbake ({}) reads: it reads {:?}; re-bake the table \
                 with this version, or verify it with the brdfbake that wrote it",
                p.display(),
                crate::meta::VERSION,
                crate::meta::SCHEMA
            )));
        }
    }
    if matches!(ext, "exr" | "ktx2") || schema.as_deref() == Some(crate::meta::SCHEMA) {
        let rb = super::inspect::read(p)?;
        let has_sidecar = rb.sidecar.is_some();
        let table = rb.table.ok_or_else(|| {
            if has_sidecar {
                return CliError::input(format!(
                    "{}: a table of `measured --out` (kind {}): nothing to recompute it from but the \
                     measured file; run `brdfbake measured` again",
                    p.display(),
                    super::MEASURED_TABLE_KIND
                ));
            }
            CliError::input(format!(
                "{}: verify needs the JSON sidecar next to the texture (it says what to recompute)",
                p.display()
            ))
        })?;
        let lut = rb.lut.ok_or_else(|| {
            CliError::input(format!(
                "{}: no texture found next to the sidecar",
                p.display()
            ))
        })?;
        jobs.push((a.target.clone(), table.spec, lut, rb.scale));
    } else {
        // a .json without a sidecar's schema is read as a preset; say so when that fails,
        // so that a damaged sidecar is not reported only in a preset's terms
        let presets = super::bake::resolve(std::slice::from_ref(&a.target)).map_err(|mut e| {
            if ext == "json" {
                e.msg = format!(
                    "{} (verify reads a .json file as a table's sidecar when its \"schema\" is {:?}, otherwise as a preset; \
                     this one has {})",
                    e.msg,
                    crate::meta::SCHEMA,
                    match &schema {
                        Some(sc) => format!("\"schema\": {sc:?}"),
                        None => "no readable \"schema\"".into(),
                    }
                );
            }
            e
        })?;
        for preset in presets {
            for t in &preset.tables {
                let lut = crate::table::bake(&t.spec)
                    .map_err(|e| CliError::input(format!("preset {}: {e}", preset.name)))?;
                jobs.push((
                    format!("{}/{}", preset.name, t.spec.name),
                    t.spec.clone(),
                    lut,
                    1.0,
                ));
            }
        }
    }
    let mut failed = Vec::new();
    let mut docs = Vec::new();
    for (label, spec, lut, scale) in &jobs {
        let (n, errs) = verify_lut(spec, lut, *scale).map_err(CliError::input)?;
        let f16 = spec.storage == crate::table::Storage::F16 && *scale > 0.0;
        if !a.json {
            outln!("{label}: {n} texels recomputed at tolerance {REFERENCE_TOLERANCE:e}");
        }
        let mut chans = Vec::new();
        for (c, (e, idx, stored, exact)) in errs.iter().enumerate() {
            let name = &lut.channels[c].name;
            let ok = *e <= a.tolerance;
            if !ok {
                failed.push(format!("{label} {name}"));
            }
            if !a.json {
                outln!(
                    "  {name:<12} max error {e:.3e} at texel {:?} (stored {stored:.12}, exact {exact:.12}) {}",
                    &idx[..lut.axes.len()],
                    if ok { "ok" } else { "OVER TOLERANCE" }
                );
            }
            chans.push(json!({"channel": name, "max_error": e, "texel": &idx[..lut.axes.len()], "stored": stored, "exact": exact, "ok": ok}));
        }
        if f16 && !a.json {
            outln!("  note: f16 storage rounds by up to 4.9e-4 relative; pass --tolerance 1e-3 to check such files");
        }
        docs.push(json!({"table": label, "texels_checked": n, "channels": chans}));
    }
    if a.json {
        let doc = json!({"tolerance": a.tolerance, "reference_tolerance": REFERENCE_TOLERANCE, "ok": failed.is_empty(), "tables": docs});
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(CliError::env(format!(
            "over the tolerance {:e}: {}",
            a.tolerance,
            failed.join(", ")
        )))
    }
}

/// The `"schema"` string of a .json file, if it is readable JSON with one (a sidecar says
/// `brdfbake.lut/1`, a preset `brdfbake.preset/1`). Reads at most the preset size limit.
fn json_schema(p: &Path) -> Option<String> {
    let f = std::fs::File::open(p).ok()?;
    if !f.metadata().ok()?.is_file() {
        return None;
    }
    let mut b = Vec::new();
    std::io::Read::read_to_end(&mut std::io::Read::take(f, 64 << 20), &mut b).ok()?;
    let v: serde_json::Value = serde_json::from_slice(&b).ok()?;
    v.get("schema")?.as_str().map(str::to_string)
}
