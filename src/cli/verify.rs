//! `brdfbake verify PRESET|FILE`: recompute a spread of texels at high accuracy and gate on
//! the max error per channel.

use super::CliError;
use crate::lut::Lut;
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
    /// Recompute every texel, not a spread of them (corners, edge midpoints, the centre
    /// and 64 pseudo-random texels).
    #[arg(long)]
    pub all: bool,
    /// Print one JSON document instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

/// How far the sidecar's fit error (3 significant digits, `{:.2e}` of an f32) may be from a
/// refit's: half a unit in the third digit of a mantissa in [1, 10) is at most 5·10⁻³ of the
/// value, and the f32 rounding adds 6·10⁻⁸.
pub const FIT_ERROR_DIGITS: f64 = 5.001e-3;

/// The distinct roughness lines (kind's axis 1) of `texels` (stored order).
fn refit_js(table: &crate::preset::PresetTable, texels: &[[usize; 3]]) -> Vec<usize> {
    let js: BTreeSet<usize> = texels
        .iter()
        .map(|&i| table.texel_to_kind_order(i)[1])
        .collect();
    js.into_iter().collect()
}

fn refit_line_count(table: &crate::preset::PresetTable, texels: &[[usize; 3]]) -> usize {
    refit_js(table, texels).len()
}

/// The refit texel of every texel of `texels` (stored order) of an `ltc` table: their
/// roughness lines refitted ([`crate::table::ltc::refit_lines`]). `None` when `deadline`
/// passed first.
fn refit_texels(
    table: &crate::preset::PresetTable,
    texels: &[[usize; 3]],
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Option<Vec<crate::kernels::ltc_fit::LtcTexel>>, String> {
    let js = refit_js(table, texels);
    let stop = || deadline.is_some_and(|d| d.passed());
    let Some(lines) = crate::table::ltc::refit_lines(&table.spec, &js, &stop)? else {
        return Ok(None);
    };
    Ok(Some(
        texels
            .iter()
            .map(|&i| {
                let k = table.texel_to_kind_order(i);
                let l = js.binary_search(&k[1]).expect("a refit line");
                lines[l][k[0]]
            })
            .collect(),
    ))
}

/// How much more a reference value at [`REFERENCE_TOLERANCE`] costs than a texel at the
/// default tolerance 1e-7, for the time estimate: the rules' error falls like h^7 to h^15,
/// so 1000 times tighter takes ~3 to ~10 times the nodes; 10 is the guide's upper end.
const REFERENCE_COST_FACTOR: f64 = 10.0;

/// The estimated cost of recomputing `n` texels of table `t`.
fn recompute_time(t: &crate::preset::PresetTable, n: usize) -> crate::resources::TimeEstimate {
    let e = crate::resources::estimate_table_time(t);
    let texels: f64 = t.spec.axes.iter().map(|a| a.size as f64).product();
    let k = REFERENCE_COST_FACTOR * n as f64 / texels.max(1.0);
    crate::resources::TimeEstimate {
        evaluations: e.evaluations * k,
        cpu_seconds: e.cpu_seconds * k,
    }
}

/// The estimated cost of the refit that checks the matrix channels of `checked` texels of
/// an `ltc` table ([`refit_texels`]): each checked texel's whole roughness line is refitted
/// as the bake fits it, so at most `min(checked, lines)` of the table's lines, each its
/// share of the bake's estimate ([`crate::resources::estimate_table_time`], which counts the
/// fit); nothing for a table without matrix channels or of another kind.
fn refit_time(t: &crate::preset::PresetTable, checked: usize) -> crate::resources::TimeEstimate {
    let refits = t.spec.kind == crate::table::TableKind::Ltc
        && crate::table::ltc::ltc_channels(&t.spec)
            .iter()
            .any(|c| c.is_matrix());
    let lines = t.spec.axes.get(1).map_or(1, |a| a.size).max(1) as f64;
    let k = if refits {
        (checked as f64).min(lines) / lines
    } else {
        0.0
    };
    let e = crate::resources::estimate_table_time(t);
    crate::resources::TimeEstimate {
        evaluations: e.evaluations * k,
        cpu_seconds: e.cpu_seconds * k,
    }
}

/// How many texels [`sample_texels`] (or `--all`) checks in a table of `dims`.
fn checked_count(dims: [usize; 3], all: bool) -> usize {
    let n = dims[0] * dims[1] * dims[2];
    if all {
        n
    } else {
        n.min(27 + RANDOM_SAMPLES)
    }
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

/// Every texel of `lut`, in texel order.
pub fn all_texels(lut: &Lut) -> Vec<[usize; 3]> {
    let dims = [lut.dim(0), lut.dim(1), lut.dim(2)];
    let mut v = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                v.push([x, y, z]);
            }
        }
    }
    v
}

/// Compares the given texels of `lut` (stored values divided by `scale`) with the values
/// recomputed from `spec` at [`REFERENCE_TOLERANCE`].
/// `None` when `deadline` passed first (checked before every texel).
pub fn verify_texels(
    table: &crate::preset::PresetTable,
    lut: &Lut,
    scale: f64,
    texels: &[[usize; 3]],
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Option<(usize, Vec<ChannelError>)>, String> {
    let stopped = std::sync::atomic::AtomicBool::new(false);
    let exact: Vec<Result<Vec<f64>, String>> = texels
        .par_iter()
        .map(|idx| {
            use std::sync::atomic::Ordering::Relaxed;
            if stopped.load(Relaxed) || deadline.is_some_and(|d| d.passed()) {
                stopped.store(true, Relaxed);
                return Ok(Vec::new());
            }
            // (the texel's own coordinate; exact_at applies the clamp, and an ltc table's
            // sphere channel depends on the unclamped position)
            let x = crate::lut::texel_nominal_coordinates(&lut.axes, idx);
            crate::readback::exact_at(&table.spec, &table.to_kind_order(&x), REFERENCE_TOLERANCE)
                .map(|r| table.stored_values(&r.0))
        })
        .collect();
    if stopped.into_inner() {
        return Ok(None);
    }
    let nc = lut.channels.len();
    let mut out = vec![(0.0, [0; 3], 0.0, 0.0); nc];
    for (k, (idx, ex)) in texels.iter().zip(exact).enumerate() {
        let ex = ex?;
        for c in 0..nc {
            let stored = lut.texel(*idx, c) as f64 / scale;
            let d = (stored - ex[c]).abs() / ex[c].abs().max(1.0);
            // (the first texel stands for a channel without error: its values, not zeros)
            if d > out[c].0 || d.is_nan() || k == 0 {
                out[c] = (d, *idx, stored, ex[c]);
            }
        }
    }
    Ok(Some((texels.len(), out)))
}

/// Per channel: (largest |lookup − exact| measured at cell middles, the cell middle's
/// physical coordinates, lookup, exact).
pub type LookupError = (f64, Vec<f64>, f64, f64);

/// The middle of the cell of `lut` that starts at texel `idx` (the cell before it on an
/// axis' last texel; an axis of one texel stays at it), in physical coordinates: where linear
/// interpolation errs the most along every axis at once.
///
/// A critical-angle axis is halved in its parameter, at the critical cosine of the middle's
/// relative index (as a lookup there places it).
pub fn cell_middle(lut: &Lut, idx: &[usize; 3]) -> Vec<f64> {
    let mut x: Vec<f64> = lut
        .axes
        .iter()
        .enumerate()
        .map(|(k, a)| {
            if a.size == 1 {
                return a.coord(0);
            }
            let i = idx[k].min(a.size - 2);
            0.5 * (a.coord(i) + a.coord(i + 1))
        })
        .collect();
    let c = crate::lut::critical_cosine_at(&lut.axes, &x);
    for (k, a) in lut.axes.iter().enumerate() {
        if a.warp.is_coupled() && a.size > 1 {
            let i = idx[k].min(a.size - 2);
            let p = 0.5 * (a.parameter(i) + a.parameter(i + 1));
            x[k] = a.clamped(a.warp.coordinate_at(p, c));
        }
    }
    x
}

/// Measures the lookup error between texels: at the middle of the cell of every texel of
/// `texels`, the ideal lookup of `lut` (stored values divided by `scale`) against the value
/// recomputed from `spec` at [`REFERENCE_TOLERANCE`]. `None` when `deadline` passed first.
pub fn verify_lookups(
    table: &crate::preset::PresetTable,
    lut: &Lut,
    scale: f64,
    texels: &[[usize; 3]],
    deadline: Option<&crate::deadline::Deadline>,
) -> Result<Option<(usize, Vec<LookupError>)>, String> {
    let mut points: Vec<Vec<f64>> = texels.iter().map(|t| cell_middle(lut, t)).collect();
    points.sort_by(|a, b| a.partial_cmp(b).expect("finite"));
    points.dedup();
    let stopped = std::sync::atomic::AtomicBool::new(false);
    let exact: Vec<Result<Vec<f64>, String>> = points
        .par_iter()
        .map(|x| {
            use std::sync::atomic::Ordering::Relaxed;
            if stopped.load(Relaxed) || deadline.is_some_and(|d| d.passed()) {
                stopped.store(true, Relaxed);
                return Ok(Vec::new());
            }
            crate::readback::exact_at(&table.spec, &table.to_kind_order(x), REFERENCE_TOLERANCE)
                .map(|r| table.stored_values(&r.0))
        })
        .collect();
    if stopped.into_inner() {
        return Ok(None);
    }
    let nc = lut.channels.len();
    let mut out: Vec<LookupError> = vec![(0.0, Vec::new(), 0.0, 0.0); nc];
    for (x, ex) in points.iter().zip(exact) {
        let ex = ex?;
        let got = lut.lookup(x);
        for c in 0..nc {
            let v = got[c] / scale;
            let d = (v - ex[c]).abs();
            if d > out[c].0 || d.is_nan() || out[c].1.is_empty() {
                out[c] = (d, x.clone(), v, ex[c]);
            }
        }
    }
    Ok(Some((points.len(), out)))
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
    // a fit's sidecar (`brdfbake fit --max-error`): its function against the exact integral
    if ext == "json" && p.is_file() {
        let head = crate::input::read_head(p, 4096).unwrap_or_default();
        if String::from_utf8_lossy(&head).contains("\"brdfbake.fit/1\"") {
            let bytes = crate::input::read_regular(p, 64 << 20, "a fit sidecar")
                .map_err(|e| CliError::input(e.to_string()))?;
            let doc: serde_json::Value = serde_json::from_slice(&bytes)
                .map_err(|e| CliError::input(format!("{}: not JSON: {e}", p.display())))?;
            if doc["schema"] == "brdfbake.fit/1" {
                return super::fit::verify_sidecar(p, &doc, a.json, &a.guards);
            }
        }
    }
    if p.is_file() && !matches!(ext, "json" | "exr" | "ktx2" | "dds" | "png") {
        return Err(CliError::input(format!(
            "{}: not a file verify reads: give a preset (a name or a .json file), a .exr, .ktx2, .dds or png-data .png \
             texture brdfbake wrote, or its .json sidecar",
            p.display(),
        )));
    }
    /// (label, table, texels, scale, lookup_error, fit_error section, what is checked)
    type Job = (
        String,
        crate::preset::PresetTable,
        Lut,
        f64,
        serde_json::Value,
        Option<serde_json::Value>,
        Checked,
    );
    let threads = rayon::current_num_threads();
    // (label, table, texels, scale, the sidecar's lookup_error: the file's, or computed for
    // a table baked here)
    // (and the sidecar's ltc.fit_error section, for an ltc table read from files)
    let mut jobs: Vec<Job> = Vec::new();
    let deadline;
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
    if matches!(ext, "exr" | "ktx2" | "dds" | "png")
        || schema.as_deref() == Some(crate::meta::SCHEMA)
    {
        // the files' bytes, the texels as f32 and their f64 exact values: ~4 times the files
        let bytes = super::inspect::file_bytes(p);
        let d = a.guards.admit(&super::guards::Work {
            what: "this verify",
            memory: 4 * bytes + (1 << 20),
            memory_detail: format!("{bytes} bytes of files, read and recomputed"),
            time: Default::default(),
            threads,
            smaller: "verify a smaller table",
        })?;
        let rb = super::inspect::read(p)?;
        let has_sidecar = rb.sidecar.is_some();
        let table = rb.table.ok_or_else(|| {
            if has_sidecar {
                return CliError::input(format!(
                    "{}: a table of `measured --out` (kind {}): nothing to recompute it from but the \
                     measured file; run `brdfbake measured` again",
                    p.display(),
                    crate::meta::MEASURED_TABLE_KIND
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
        // the time, now that the table is known
        // (every checked texel and the middle of its cell)
        let checked = checked_count([lut.dim(0), lut.dim(1), lut.dim(2)], a.all);
        let time = recompute_time(&table, 2 * checked) + refit_time(&table, checked);
        crate::resources::check_time_of(
            "this verify",
            "verify fewer texels (without --all)",
            &time,
            threads,
            a.guards.max_time,
        )
        .map_err(CliError::input)?;
        deadline = Some(d);
        // (a texture read back has no error estimates: the sidecar's statement is the one)
        let stated = rb
            .sidecar
            .as_ref()
            .and_then(|s| s.get("lookup_error").cloned())
            .unwrap_or_else(|| crate::meta::lookup_error(&table, &lut));
        let fit_error = rb
            .sidecar
            .as_ref()
            .and_then(|s| s.pointer("/ltc/fit_error").cloned());
        jobs.push((
            a.target.clone(),
            table,
            lut,
            rb.scale,
            stated,
            fit_error,
            Checked::File,
        ));
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
        let mut time = crate::resources::estimate_time(&presets);
        for t in presets.iter().flat_map(|p| &p.tables) {
            let dims = [0, 1, 2].map(|k| t.spec.axes.get(k).map_or(1, |x| x.size));
            let checked = checked_count(dims, a.all);
            time = time + recompute_time(t, 2 * checked) + refit_time(t, checked);
        }
        let est = crate::resources::estimate(&presets, Some(&[]));
        let d = a.guards.admit(&super::guards::Work {
            what: "this verify",
            memory: est.peak(),
            memory_detail: format!("{} texels baked in memory", est.texels),
            time,
            threads,
            smaller: "verify fewer or smaller tables, or fewer texels (without --all)",
        })?;
        deadline = Some(d);
        for preset in presets {
            for t in &preset.tables {
                let opts = crate::table::BakeOptions {
                    deadline: deadline.as_ref(),
                    accept_error_estimate: t.accept_error_estimate,
                };
                let lut = crate::table::bake_with(&t.spec, &opts)
                    .map_err(|e| super::bake_error(&preset.name, e))?;
                let label = format!("{}/{}", preset.name, t.spec.name);
                let lut = t.stored(lut);
                if t.spec.storage.is_unorm() {
                    // the texels as stored: value × scale rounded to its code, read back
                    let mut scaled = lut;
                    for v in scaled.data.iter_mut() {
                        *v = (*v as f64 * t.scale) as f32;
                    }
                    let stated = crate::meta::lookup_error(t, &scaled);
                    let stored =
                        crate::encode::unorm::quantized(&t.spec.name, &scaled, t.spec.storage)
                            .map_err(|e| CliError::input(format!("preset {}: {e}", preset.name)))?;
                    jobs.push((
                        label,
                        t.clone(),
                        stored,
                        t.scale,
                        stated,
                        None,
                        Checked::Baked,
                    ));
                    continue;
                }
                // (baked here, the texels are the values: no scale applied)
                let values = crate::preset::PresetTable {
                    scale: 1.0,
                    ..t.clone()
                };
                let stated = crate::meta::lookup_error(&values, &lut);
                jobs.push((label, t.clone(), lut, 1.0, stated, None, Checked::Baked));
            }
        }
    }
    let mut failed = Vec::new();
    let mut docs = Vec::new();
    for (label, table, lut, scale, sidecar, fit_error, checked) in &jobs {
        let spec = &table.spec;
        let texels = if a.all {
            all_texels(lut)
        } else {
            sample_texels(lut)
        };
        let stopped = || super::guards::stopped("this verify", deadline.as_ref().expect("set"));
        let (n, errs) = verify_texels(table, lut, *scale, &texels, deadline.as_ref())
            .map_err(CliError::input)?
            .ok_or_else(stopped)?;
        let (cells, lookups) = verify_lookups(table, lut, *scale, &texels, deadline.as_ref())
            .map_err(CliError::input)?
            .ok_or_else(stopped)?;
        let f16 = spec.storage == crate::table::Storage::F16 && *scale > 0.0;
        // a normalized-integer texel is off by up to half a step (÷ scale) by construction:
        // the threshold is the tolerance plus that bound (the sidecar's rounding_error_bound)
        let rounding = spec
            .storage
            .quantization_step()
            .map_or(0.0, |step| step / 2.0 / scale);
        let threshold = a.tolerance + rounding;
        if !a.json {
            outln!(
                "{label}: {}; {n} texels recomputed exactly (reference tolerance {REFERENCE_TOLERANCE:e})",
                checked.what()
            );
            outln!(
                "  exit 1 if a texel's error (relative above 1) exceeds {threshold:.3e}: --tolerance {:e}{}; the lookups between texels below are the table's interpolation error, for information",
                a.tolerance,
                if rounding > 0.0 {
                    format!(
                        " plus the {} storage's rounding, half a step: {rounding:.3e}",
                        spec.storage.name()
                    )
                } else {
                    String::new()
                }
            );
        }
        let mut chans = Vec::new();
        // an ltc table's matrix entries have no exact value to recompute (exact_at gives NaN):
        // the fit is defined at its texels, by a fixed path along each roughness line, so a
        // refit of the checked texels' lines gives them bit for bit
        let no_exact = |exact: f64| spec.kind.is_ltc() && exact.is_nan();
        let refit = if errs.iter().any(|e| no_exact(e.3)) {
            refit_texels(table, &texels, deadline.as_ref())
                .map_err(CliError::input)?
                .ok_or_else(stopped)?
        } else {
            Vec::new()
        };
        if !refit.is_empty() && !a.json {
            outln!(
                "  (the matrix channels against a refit of the checked texels' {} roughness lines: the fit's fixed path gives the same bits)",
                refit_line_count(table, &texels)
            );
        }
        for (c, (e, idx, stored, exact)) in errs.iter().enumerate() {
            let name = &lut.channels[c].name;
            if no_exact(*exact) {
                // the refit's value of stored channel c at every checked texel
                let mut worst = (0.0f64, [0usize; 3], f64::NAN, f64::NAN);
                for (idx, t) in texels.iter().zip(&refit) {
                    let want =
                        table.stored_values(&crate::table::ltc::refit_matrix_values(spec, t))[c];
                    let got = lut.texel(*idx, c) as f64 / scale;
                    let d = (got - want).abs() / want.abs().max(1.0);
                    if d > worst.0 || d.is_nan() || worst.2.is_nan() {
                        worst = (d, *idx, got, want);
                    }
                }
                let (e, idx, stored, want) = worst;
                let ok = e <= threshold;
                if !ok {
                    failed.push(format!("{label} {name}"));
                }
                if !a.json {
                    outln!(
                        "  {name:<12} max error {e:.3e} at texel {:?} (stored {stored:.12}, refit {want:.12}) {}",
                        &idx[..lut.axes.len()],
                        if ok { "ok" } else { "OVER THE THRESHOLD" }
                    );
                }
                chans.push(json!({"channel": name, "recomputed_by": "refit", "max_error": e, "texel": &idx[..lut.axes.len()], "stored": stored, "refit": want, "ok": ok, "threshold": threshold}));
                continue;
            }
            // (relative above 1, like the error)
            let ok = *e <= threshold;
            if !ok {
                failed.push(format!("{label} {name}"));
            }
            if !a.json {
                outln!(
                    "  {name:<12} max error {e:.3e} at texel {:?} (stored {stored:.12}, exact {exact:.12}) {}",
                    &idx[..lut.axes.len()],
                    if ok { "ok" } else { "OVER THE THRESHOLD" }
                );
            }
            chans.push(json!({"channel": name, "max_error": e, "texel": &idx[..lut.axes.len()], "stored": stored, "exact": exact, "ok": ok, "threshold": threshold}));
        }
        if f16 && !a.json {
            outln!("  note: f16 storage rounds by up to 4.9e-4 relative; pass --tolerance 1e-3 to check such files");
        }
        // lookups between texels: measured with ideal weights; 8-bit hardware weights move
        // them by at most the bound (not gated: the interpolation error is the resolution's)
        if !a.json {
            outln!(
                "  lookups between texels ({cells} cell middles, ideal filtering; hardware = + 8-bit weight rounding bound; not in the exit code):"
            );
        }
        let mut lookup_docs = Vec::new();
        for (c, (e, at, got, exact)) in lookups.iter().enumerate() {
            let name = &lut.channels[c].name;
            if no_exact(*exact) {
                if !a.json {
                    outln!("  {name:<12} not measured: no exact value between the fit's texels");
                }
                lookup_docs.push(json!({"channel": name, "checked": false}));
                continue;
            }
            let num = |k: &str| sidecar[k][name.as_str()].as_f64().unwrap_or(f64::NAN);
            let (estimate, bound) = (num("interpolation_estimate"), num("weight_rounding_bound"));
            let worst = num("ideal_filtering");
            let within = *e <= worst;
            if !a.json {
                outln!(
                    "  {name:<12} max error {e:.3e} at {at:?} (lookup {got:.12}, exact {exact:.12}); hardware up to {:.3e}; sidecar: worst case {worst:.3e} ({}), smooth-table estimate {estimate:.3e}, 8-bit weights {bound:.3e}",
                    e + bound,
                    if within { "holds" } else { "EXCEEDED: the function has a peak or dip between texel centres there" }
                );
            }
            lookup_docs.push(json!({"channel": name, "ideal_filtering_max_error": e, "at": at, "lookup": got, "exact": exact, "hardware_filtering_max_error": e + bound, "weight_rounding_bound": bound, "sidecar_ideal_filtering": worst, "within_sidecar_worst_case": within, "sidecar_interpolation_estimate": estimate}));
        }
        let mut doc = json!({"table": label, "checked": checked.name(), "texels_checked": n, "threshold": threshold, "channels": chans, "lookups": {"cell_middles_checked": cells, "in_exit_code": false, "channels": lookup_docs}});
        // the sidecar's per-texel fit error against the refit's
        if !refit.is_empty() {
            match fit_error {
                Some(fe) => {
                    let mut fit_docs = Vec::new();
                    for (k, ch) in crate::table::ltc::fit_channels().iter().enumerate() {
                        let name = ch.name.as_str();
                        let side = fe
                            .get(name)
                            .and_then(|v| v.get("rows"))
                            .and_then(|r| r.as_array())
                            .and_then(|r| crate::meta::parse_texel_rows(r))
                            .filter(|v| v.len() == lut.data.len() / lut.channels.len().max(1));
                        let Some(side) = side else {
                            failed.push(format!("{label} ltc.fit_error.{name}"));
                            if !a.json {
                                outln!("  fit error {name:<9} MISSING or malformed in the sidecar (ltc.fit_error.{name}.rows)");
                            }
                            fit_docs.push(json!({"channel": name, "ok": false, "reason": "missing or malformed rows"}));
                            continue;
                        };
                        let mut worst = (0.0f64, [0usize; 3], f64::NAN, f64::NAN);
                        for (idx, t) in texels.iter().zip(&refit) {
                            let want = crate::table::ltc::refit_fit_values(t)[k];
                            let got = side[idx[0] + idx[1] * lut.dim(0)] as f64;
                            let d = if want == 0.0 {
                                if got == 0.0 {
                                    0.0
                                } else {
                                    f64::INFINITY
                                }
                            } else {
                                (got - want).abs() / want.abs()
                            };
                            if d > worst.0 || d.is_nan() || worst.2.is_nan() {
                                worst = (d, *idx, got, want);
                            }
                        }
                        let (d, idx, got, want) = worst;
                        let ok = d <= FIT_ERROR_DIGITS;
                        if !ok {
                            failed.push(format!("{label} ltc.fit_error.{name}"));
                        }
                        if !a.json {
                            outln!(
                                "  fit error {name:<9} max relative difference {d:.1e} at texel {:?} (sidecar {got:.3e}, refit {want:.6e}) {}",
                                &idx[..lut.axes.len()],
                                if ok { "ok" } else { "DIFFERS" }
                            );
                        }
                        fit_docs.push(json!({"channel": name, "max_relative_difference": d, "texel": &idx[..lut.axes.len()], "sidecar": got, "refit": want, "ok": ok, "threshold": FIT_ERROR_DIGITS}));
                    }
                    doc["fit_error"] = json!(fit_docs);
                }
                None => {
                    if !a.json {
                        outln!("  fit error: not checked (no sidecar ltc.fit_error: verify a baked file for that)");
                    }
                }
            }
        }
        if rounding > 0.0 {
            doc["storage"] = json!(spec.storage.name());
            doc["storage_rounding_bound"] = json!(rounding);
            doc["threshold"] = json!(threshold);
            doc["threshold_meaning"] = json!("--tolerance plus the storage's rounding bound (half a quantization step / scale): a texel is ok within it");
        }
        docs.push(doc);
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

/// What `verify` checked: a file brdfbake wrote, or a preset baked in memory.
#[derive(Clone, Copy, Debug)]
enum Checked {
    File,
    Baked,
}

impl Checked {
    fn what(self) -> &'static str {
        match self {
            Checked::File => "checking the file",
            Checked::Baked => {
                "checking the preset baked in memory (not the files in out/: give a file to check what was written)"
            }
        }
    }

    fn name(self) -> &'static str {
        match self {
            Checked::File => "file",
            Checked::Baked => "baked-in-memory",
        }
    }
}

/// The `"schema"` string of a .json file, if it is readable JSON with one (a sidecar says
/// `brdfbake.lut/1`, a preset `brdfbake.preset/1`). Reads at most the preset size limit.
fn json_schema(p: &Path) -> Option<String> {
    // (through input.rs: a FIFO is refused before it is opened, never blocks)
    let b = crate::input::read_regular(p, 64 << 20, "a .json file").ok()?;
    let v: serde_json::Value = serde_json::from_slice(&b).ok()?;
    v.get("schema")?.as_str().map(str::to_string)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(channels: &str) -> crate::preset::PresetTable {
        let text = format!(
            r#"{{ "schema": "brdfbake.preset/1", "tables": [ {{ "name": "t", "kind": "ltc",
            "model": {{ "ndf": "ggx", "masking": "smith-height-correlated" }},
            "ltc": {{ "channels": {channels} }},
            "axes": {{ "cos_theta_v": {{ "size": 16, "range": [0.1, 1] }},
                      "roughness": {{ "size": 8, "range": [0.1, 1], "quantity": "perceptual" }} }},
            "formats": ["exr"] }} ] }}"#
        );
        crate::preset::parse(&text, "test", "t").unwrap().tables[0].clone()
    }

    /// The refit of an `ltc` table's matrix channels costs the checked texels' roughness
    /// lines (at most all 8 of them: the whole bake's estimate), and nothing without them.
    #[test]
    fn refit_is_in_the_time_estimate() {
        let m = table(r#"["m00", "m20", "m02", "m22"]"#);
        let bake = crate::resources::estimate_table_time(&m).cpu_seconds;
        assert!(bake > 0.0);
        let at = |t: &crate::preset::PresetTable, n| refit_time(t, n).cpu_seconds;
        assert!((at(&m, 2) - bake * 2.0 / 8.0).abs() <= 1e-12 * bake);
        assert!((at(&m, 91) - bake).abs() <= 1e-12 * bake);
        assert_eq!(at(&table(r#"["norm", "fresnel"]"#), 91), 0.0);
    }
}
