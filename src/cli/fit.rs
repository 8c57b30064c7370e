//! `brdfbake fit PRESET`: minimax fits of a table's exact function (src/fit/), their Pareto
//! front (operations against max error), the published fits of the same function measured
//! the same way, and the chosen fit emitted as functions (src/encode/function.rs) with a
//! JSON sidecar.

use super::CliError;
use crate::encode::function;
use crate::fit::{reference, search, target};
use crate::numfmt::num;
use serde_json::json;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// A preset (a name such as karis-envbrdf or sheen-charlie, or a .json file).
    pub preset: String,
    /// The table to fit, when the preset has several.
    #[arg(long)]
    pub table: Option<String>,
    /// Emit the cheapest fit whose max error (plus its f32 rounding bound) is at most this.
    #[arg(long, value_name = "ERROR")]
    pub max_error: Option<f64>,
    /// Minimize the absolute or the relative error (relative to max(|exact|, 1e-3 max|exact|)).
    /// Instead of fitting: the smallest texture (texels per axis, 4 to 256) whose filtered
    /// lookups stay within this error, by the sidecar's lookup-error bounds
    #[arg(long, value_name = "ERROR", conflicts_with = "max_error")]
    pub texture_error: Option<f64>,
    #[arg(long, default_value = "absolute", value_parser = ["absolute", "relative"])]
    pub weight: String,
    /// Languages to emit the chosen fit in (comma-separated): glsl, hlsl, wgsl, c, rust.
    #[arg(long, value_delimiter = ',', default_value = "glsl,hlsl,wgsl,c,rust")]
    pub emit: Vec<String>,
    /// Directory for the functions and the sidecar (nothing is written without --max-error).
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// One JSON document (schema brdfbake.fit/1) instead of the text table.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

pub fn run(a: FitArgs) -> Result<(), CliError> {
    for l in &a.emit {
        if function::dialect(l).is_none() {
            return Err(CliError::input(format!(
                "--emit {l}: unknown language (accepted: {})",
                function::LANGUAGES.join(", ")
            )));
        }
    }
    if let Some(e) = a.max_error {
        if !(e.is_finite() && e > 0.0) {
            return Err(CliError::input(format!(
                "--max-error must be a positive number, got {}",
                num(e)
            )));
        }
    }
    let weight = match a.weight.as_str() {
        "relative" => search::Weight::Relative,
        _ => search::Weight::Absolute,
    };
    let presets = super::bake::resolve(std::slice::from_ref(&a.preset))?;
    let preset = &presets[0];
    let t = super::compare::pick_table(preset, a.table.as_deref())?;
    if let Some(e) = a.texture_error {
        return texture_sizes(&a, preset, t, e);
    }
    let axes = target::grid_axes(&t.spec).map_err(CliError::input)?;
    let points: usize = axes.iter().map(|x| x.size).product();
    let mut grid = t.clone();
    grid.spec.axes = axes;
    let mut time = crate::resources::estimate_table_time(&grid);
    time.cpu_seconds += points as f64 * crate::fit::emit::SECONDS_PER_POINT;
    let deadline = a.guards.admit(&super::guards::Work {
        what: "this fit",
        memory: points as u64 * crate::fit::emit::BYTES_PER_POINT,
        memory_detail: format!("{points} validation points"),
        time,
        threads: rayon::current_num_threads(),
        smaller: "fit a table of fewer texels",
    })?;
    let Some((tg, front)) =
        crate::fit::emit::front(&t.spec, weight, Some(&deadline)).map_err(CliError::input)?
    else {
        return Err(super::guards::stopped("this fit", &deadline));
    };
    let refs: Vec<(reference::Reference, reference::Measured)> = reference::all()
        .into_iter()
        .filter(|r| reference::preset_of(r.name) == Some(preset.name.as_str()))
        .map(|r| {
            let m = reference::measure(&r.program, &tg);
            (r, m)
        })
        .collect();
    let chosen = a
        .max_error
        .map(|e| {
            crate::fit::emit::choose(
                &front,
                crate::fit::emit::Goal::MaxError(e),
                &format!("{}/{}", preset.name, t.spec.name),
            )
            .map_err(CliError::env)
        })
        .transpose()?;
    let rows: Vec<serde_json::Value> = front
        .iter()
        .map(|c| {
            json!({
                "form": c.description,
                "ops": c.counts.ops,
                "special": c.counts.special,
                "constants": c.counts.constants,
                "max_error": c.error,
                "f32_bound": c.f32_bound,
            })
        })
        .collect();
    let ref_rows: Vec<serde_json::Value> = refs
        .iter()
        .map(|(r, m)| {
            json!({
                "name": r.name,
                "source": r.source,
                "ops": m.counts.ops,
                "special": m.counts.special,
                "max_error": m.error,
                "at": m.argmax,
            })
        })
        .collect();
    if a.json {
        let doc = json!({
            "schema": "brdfbake.fit/1",
            "preset": preset.name,
            "table": t.spec.name,
            "channels": tg.channels,
            "weight": weight.name(),
            "validation_points": tg.points(),
            "pareto": rows,
            "references": ref_rows,
        });
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
    } else {
        outln!(
            "{}/{}: {} error against the exact integral at {} validation points (texels, midpoints, ends)",
            preset.name,
            t.spec.name,
            weight.name(),
            tg.points()
        );
        outln!(
            "{:>4} {:>3} {:>6}  {:>10} {:>9}  form",
            "ops",
            "sp",
            "const",
            "max error",
            "f32 bound"
        );
        for c in &front {
            outln!(
                "{:>4} {:>3} {:>6}  {:>10.3e} {:>9.1e}  {}",
                c.counts.ops,
                c.counts.special,
                c.counts.constants,
                c.max_error(),
                c.f32_bound.iter().cloned().fold(0.0, f64::max),
                c.description
            );
        }
        for (r, m) in &refs {
            outln!(
                "{:>4} {:>3} {:>6}  {:>10.3e} {:>9}  {} (published; worst at {:?})",
                m.counts.ops,
                m.counts.special,
                m.counts.constants,
                m.max_error(),
                "",
                r.name,
                m.argmax[m
                    .error
                    .iter()
                    .enumerate()
                    .max_by(|x, y| x.1.total_cmp(y.1))
                    .map_or(0, |x| x.0)]
            );
        }
    }
    if let Some(c) = chosen {
        let base = format!("{}-{}-fit", preset.name, t.spec.name);
        let files = crate::fit::emit::files(
            &preset.name,
            &t.spec.name,
            &tg,
            weight,
            c,
            &a.emit,
            &a.out,
            &base,
            Default::default(),
        );
        std::fs::create_dir_all(&a.out)
            .map_err(|e| CliError::env(format!("creating {}: {e}", a.out.display())))?;
        crate::write::write_all_atomic(&files)
            .map_err(|e| CliError::env(format!("writing the fit: {e}")))?;
        for (p, _) in &files {
            eprintln!("wrote {}", p.display());
        }
    }
    Ok(())
}

/// The table a bake's fit sidecar belongs to: from the table's sidecar `TABLE.json` in the
/// same folder, which must carry the same input hash.
fn table_beside(
    path: &std::path::Path,
    table: &str,
    hash: &str,
) -> Result<crate::preset::PresetTable, CliError> {
    let side = path.with_file_name(format!("{table}.json"));
    let bytes = crate::readback::read_bytes(&side).map_err(|e| match e {
        crate::readback::ReadError::Input(m) => CliError::input(format!(
            "{}: the fit of a bake is checked against its table's sidecar: {m}",
            path.display()
        )),
        crate::readback::ReadError::Io(m) => CliError::env(m),
    })?;
    let doc: serde_json::Value = serde_json::from_slice(&bytes)
        .map_err(|e| CliError::input(format!("{}: not valid JSON ({e})", side.display())))?;
    let t = crate::readback::table_from_sidecar(&doc)
        .map_err(|m| CliError::input(format!("{}: {m}", side.display())))?;
    let have = crate::meta::input_hash(&t);
    if have != hash {
        return Err(CliError::input(format!(
            "{}: its input hash {hash} is not its table's ({} has {have}): they come from different bakes",
            path.display(),
            side.display()
        )));
    }
    Ok(t)
}

/// Points `verify` re-evaluates a fit at, and their stream's seed.
const VERIFY_POINTS: usize = 512;
const VERIFY_SEED: u64 = 0xF17_C0DE;

/// `brdfbake verify FIT.json`: the fit of a `brdfbake.fit/1` sidecar (its preset by name)
/// re-evaluated as the code runs (f32) at [`VERIFY_POINTS`] pseudo-random points of the
/// domain against the exact integral at 1e-9. It passes when every channel is within the
/// sidecar's stated max error — measured on a grid and a check set, so between their points
/// a smooth fit can exceed it by its curvature over half a step: 5% is allowed — plus its
/// f32 bound plus the quadrature tolerance; else exit 1, naming the worst point.
pub fn verify_sidecar(
    path: &std::path::Path,
    doc: &serde_json::Value,
    json_out: bool,
    guards: &super::guards::Guards,
) -> Result<(), CliError> {
    let bad = |what: &str| {
        CliError::input(format!(
            "{}: a brdfbake.fit/1 sidecar needs {what}",
            path.display()
        ))
    };
    let preset_name = doc["preset"]
        .as_str()
        .ok_or_else(|| bad("\"preset\" (a name)"))?;
    let table_name = doc["table"].as_str().ok_or_else(|| bad("\"table\""))?;
    let fitted: crate::fit::form::Fitted = serde_json::from_value(doc["fit"].clone())
        .map_err(|e| bad(&format!("\"fit\" as brdfbake writes it ({e})")))?;
    let stated = |key: &str| -> Result<Vec<f64>, CliError> {
        doc[key]
            .as_array()
            .and_then(|v| v.iter().map(|x| x.as_f64()).collect::<Option<Vec<f64>>>())
            .ok_or_else(|| bad(&format!("\"{key}\" (a number per channel)")))
    };
    let (max_error, f32_bound) = (stated("max_error")?, stated("f32_bound")?);
    let owned;
    let t = match doc["input_hash"].as_str() {
        // a bake's fit (the preset field `fit`): its table is the one the sidecar beside it
        // describes, whatever preset file it came from
        Some(hash) => {
            owned = table_beside(path, table_name, hash)?;
            &owned
        }
        None => {
            let presets = super::bake::resolve(&[preset_name.to_string()])?;
            owned = super::compare::pick_table(&presets[0], Some(table_name))?.clone();
            &owned
        }
    };
    let inputs = target::inputs(&t.spec);
    fitted
        .check(inputs.len())
        .map_err(|m| bad(&format!("\"fit\" as brdfbake writes it ({m})")))?;
    let channels: Vec<String> = doc["channels"]
        .as_array()
        .map(|v| {
            v.iter()
                .filter_map(|x| x.as_str().map(String::from))
                .collect()
        })
        .unwrap_or_default();
    if channels.len() != max_error.len() || channels.len() != f32_bound.len() {
        return Err(bad("as many channels as max_error and f32_bound entries"));
    }
    let mut time = crate::resources::estimate_table_time(t);
    time.cpu_seconds += VERIFY_POINTS as f64 * crate::fit::emit::SECONDS_PER_POINT;
    let deadline = guards.admit(&super::guards::Work {
        what: "this verify",
        memory: VERIFY_POINTS as u64 * crate::fit::emit::BYTES_PER_POINT,
        memory_detail: format!("{VERIFY_POINTS} points"),
        time,
        threads: 1,
        smaller: "verify a smaller fit",
    })?;
    let program = fitted.program(&inputs, &channels);
    if program.outputs.len() != channels.len() {
        return Err(bad("a fit with one output per channel"));
    }
    let tol = 1e-9;
    let v = crate::deadline::scoped(&deadline, || {
        crate::fit::verify(&t.spec, &inputs, &program, VERIFY_POINTS, VERIFY_SEED, tol)
    })
    .map_err(CliError::input)?;
    if deadline.passed() {
        return Err(super::guards::stopped("this verify", &deadline));
    }
    let allowed: Vec<f64> = (0..channels.len())
        .map(|c| 1.05 * max_error[c] + f32_bound[c] + tol)
        .collect();
    let pass = (0..channels.len()).all(|c| v.error[c] <= allowed[c]);
    if json_out {
        println!(
            "{}",
            json!({"schema": "brdfbake.fit-verify/1", "file": path.display().to_string(),
                   "points": v.points, "channels": channels, "error": v.error,
                   "at": v.argmax, "allowed": allowed, "pass": pass})
        );
    } else {
        println!(
            "{}: {}/{} fit re-evaluated in f32 at {} points against the exact integral",
            path.display(),
            preset_name,
            table_name,
            v.points
        );
        for (c, name) in channels.iter().enumerate() {
            let at: Vec<String> = v.argmax[c].iter().map(|x| num(*x)).collect();
            println!(
                "  {name}: max |fit - exact| {} at ({}), allowed {} (1.05 x stated {} + f32 bound {})",
                num(v.error[c]),
                at.join(", "),
                num(allowed[c]),
                num(max_error[c]),
                num(f32_bound[c])
            );
        }
    }
    if pass {
        Ok(())
    } else {
        Err(CliError::env(format!(
            "{}: the fit misses its stated error (above)",
            path.display()
        )))
    }
}

/// `fit --texture-error E`: every size of `fit::resolution::SIZES` with its lookup-error
/// bounds (exact and 8-bit weights) and typical error, and the smallest size that holds E.
fn texture_sizes(
    a: &FitArgs,
    preset: &crate::preset::Preset,
    t: &crate::preset::PresetTable,
    e: f64,
) -> Result<(), CliError> {
    if !(e.is_finite() && e > 0.0) {
        return Err(CliError::input(format!(
            "--texture-error must be a positive number, got {e}"
        )));
    }
    let mut big = t.clone();
    for ax in &mut big.spec.axes {
        if ax.size > 1 {
            ax.size = *crate::fit::resolution::SIZES.last().expect("sizes");
        }
    }
    let deadline = a.guards.admit(&super::guards::Work {
        what: "this size search",
        memory: {
            let m = crate::resources::estimate_table(&big, &[]);
            m.kept + m.scratch
        },
        memory_detail: "the largest size's table".into(),
        time: crate::resources::estimate_table_time(&big),
        threads: rayon::current_num_threads(),
        smaller: "search a table of fewer axes",
    })?;
    let r =
        crate::fit::resolution::resolutions(preset, t, Some(&deadline)).map_err(CliError::input)?;
    let holds = |f: &dyn Fn(&crate::fit::resolution::Resolution) -> f64| {
        r.iter().find(|x| f(x) <= e).map(|x| x.size)
    };
    let (ideal, hardware, typical) = (
        holds(&|x| x.ideal),
        holds(&|x| x.hardware),
        holds(&|x| x.estimate),
    );
    if a.json {
        println!(
            "{}",
            json!({"preset": preset.name, "table": t.spec.name, "texture_error": e,
                   "sizes": r.iter().map(|x| json!({"size": x.size, "ideal_filtering": x.ideal,
                   "hardware_filtering": x.hardware, "typical": x.estimate})).collect::<Vec<_>>(),
                   "smallest": {"ideal_filtering": ideal, "hardware_filtering": hardware,
                   "typical": typical}})
        );
        return Ok(());
    }
    println!(
        "{}/{}: lookup error by texels per axis (bounds as the sidecar's lookup_error)",
        preset.name, t.spec.name
    );
    println!("  size  exact weights  8-bit weights  typical");
    for x in &r {
        println!(
            "  {:>4}  {:>13}  {:>13}  {:>7}",
            x.size,
            num(x.ideal),
            num(x.hardware),
            num(x.estimate)
        );
    }
    let say = |what: &str, s: Option<usize>| match s {
        Some(n) => println!("  {what}: {n} texels per axis hold {}", num(e)),
        None => println!(
            "  {what}: no size up to {} holds {}",
            crate::fit::resolution::SIZES.last().expect("sizes"),
            num(e)
        ),
    };
    say("bound, exact weights", ideal);
    say("bound, 8-bit weights", hardware);
    say("typical", typical);
    Ok(())
}
