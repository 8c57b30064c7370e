//! `brdfbake compare PRESET FILE`: an engine's shipped table against exact values at its own
//! texels, next to brdfbake's table of the same preset (src/engines/).

use super::CliError;
use crate::engines::{compare_table, CompareError, Comparison};
use crate::numfmt::num;
use serde_json::json;
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct CompareArgs {
    /// An engine preset (a name such as cycles-ggx-e, or a .json file) whose table has a
    /// `shipped` description: how the engine's file holds it.
    pub preset: String,
    /// The engine's shipped file (e.g. Cycles' shader.tables, three.js' DFGLUTData.js, a
    /// LUT PNG), read as the preset's `shipped` field says.
    pub file: PathBuf,
    /// The table to compare, when the preset has several.
    #[arg(long)]
    pub table: Option<String>,
    /// One JSON document (schema brdfbake.compare/1) instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

/// Largest shipped file read: a 4096² RGBA table of 32-bit floats printed as text, ~20 bytes
/// a value.
const MAX_SHIPPED_BYTES: u64 = 1400 << 20;

pub fn run(a: CompareArgs) -> Result<(), CliError> {
    let presets = super::bake::resolve(std::slice::from_ref(&a.preset))?;
    let preset = &presets[0];
    let t = pick_table(preset, a.table.as_deref())?;
    if t.shipped.is_none() {
        return Err(CliError::input(format!(
            "preset {}: table {} has no `shipped` description (how the engine's file holds it): compare takes an engine preset (brdfbake list shows them)",
            preset.name, t.spec.name
        )));
    }
    let bytes = crate::input::read_regular(&a.file, MAX_SHIPPED_BYTES, "a shipped table file")
        .map_err(CliError::from)?;
    // two bakes of the table (the preset's and the reference at a 100x tighter tolerance)
    let one = std::slice::from_ref(preset);
    let est = crate::resources::estimate(one, Some(&[crate::preset::Format::Exr]));
    let mut time = crate::resources::estimate_time(one);
    time.evaluations *= 3.0;
    time.cpu_seconds *= 3.0;
    let deadline = a.guards.admit(&super::guards::Work {
        what: "this compare",
        memory: 2 * est.peak() + bytes.len() as u64 * 8,
        memory_detail: format!(
            "{} texels baked twice in memory, and the shipped file",
            est.texels
        ),
        time,
        threads: rayon::current_num_threads(),
        smaller: "compare a smaller table",
    })?;
    let file = a.file.display().to_string();
    let c = compare_table(
        &preset.name,
        preset.source.as_ref(),
        t,
        &bytes,
        &file,
        Some(&deadline),
    )
    .map_err(|e| match e {
        CompareError::Input(m) => CliError::input(m),
        CompareError::Bake(e) => super::bake_error(&preset.name, e),
    })?;
    if a.json {
        let mut doc = serde_json::to_value(&c).expect("serializable");
        doc["schema"] = json!("brdfbake.compare/1");
        doc["source"] = json!(preset.source);
        doc["brdfbake_within_bound"] = json!(c.brdfbake_within_bound());
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
    } else {
        print_text(&c, preset.source.as_ref())?;
    }
    if !c.brdfbake_within_bound() {
        return Err(CliError::env(format!(
            "brdfbake's table {}/{} misses its bound {} against the exact values (see above)",
            c.preset,
            c.table,
            num(c.brdfbake_bound)
        )));
    }
    Ok(())
}

/// The table `table` names in `preset`, or its only table.
pub(super) fn pick_table<'p>(
    preset: &'p crate::preset::Preset,
    table: Option<&str>,
) -> Result<&'p crate::preset::PresetTable, CliError> {
    let names = || {
        preset
            .tables
            .iter()
            .map(|t| t.spec.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    match table {
        Some(n) => preset
            .tables
            .iter()
            .find(|t| t.spec.name == n)
            .ok_or_else(|| {
                CliError::input(format!(
                    "--table {n}: preset {} has no such table (its tables: {})",
                    preset.name,
                    names()
                ))
            }),
        None => match preset.tables.as_slice() {
            [t] => Ok(t),
            ts => Err(CliError::input(format!(
                "preset {} has {} tables: name one with --table ({})",
                preset.name,
                ts.len(),
                names()
            ))),
        },
    }
}

fn stats_line(s: &crate::engines::compare::Stats, dims: usize) -> String {
    format!(
        "max |error| {} at texel {} ({}): {} vs exact {}; mean {}, rms {}, mean signed {} ({} texels)",
        num(s.max_abs),
        crate::lut::texel_indices(&s.worst_texel[..dims]),
        s.worst_physical,
        num(s.worst_value),
        num(s.worst_exact),
        num(s.mean_abs),
        num(s.rms),
        num(s.mean_signed),
        s.texels
    )
}

fn print_text(c: &Comparison, source: Option<&crate::engines::Source>) -> Result<(), CliError> {
    let dims = c.dims.len();
    outln!(
        "{}/{} against {} ({} texels; {})",
        c.preset,
        c.table,
        c.file,
        c.dims
            .iter()
            .map(|d| d.to_string())
            .collect::<Vec<_>>()
            .join(" x "),
        c.storage
    );
    if let Some(s) = source {
        outln!(
            "  shipped by {}: {} ({}, {} @ {}, {})",
            s.engine,
            s.table,
            s.repository,
            s.path,
            s.commit,
            s.licence
        );
        if let Some(n) = &s.notes {
            outln!("  notes: {n}");
        }
    }
    outln!(
        "  exact: brdfbake at tolerance {} (largest error estimate {}); texels x, y, z along the file's axes, x fastest",
        num(c.reference_tolerance),
        num(c.exact_error_estimate)
    );
    for e in &c.excluded {
        outln!(
            "  left out of the verdicts: {} texel {} ({}, {} texels): {}",
            e.axis,
            e.index,
            e.at,
            e.texels,
            e.why
        );
    }
    for ch in &c.channels {
        if ch.name == ch.channel {
            outln!("  {}:", ch.name);
        } else {
            outln!("  {} (stored as {}):", ch.name, ch.channel);
        }
        outln!("    verdict: {}", ch.verdict.text);
        match &ch.shipped_regular {
            Some(r) => {
                outln!("    shipped, judged texels: {}", stats_line(r, dims));
                outln!(
                    "    shipped, with the left-out slices: {}",
                    stats_line(&ch.shipped, dims)
                );
            }
            None => outln!("    shipped: {}", stats_line(&ch.shipped, dims)),
        }
        match c.reference_is_own_bake {
            Some(why) => outln!(
                "    brdfbake: not compared ({why}: the reference is brdfbake's own bake at the table's tolerance, so the difference is 0 by construction; its error is bounded by the bake's error estimate, {})",
                num(c.exact_error_estimate)
            ),
            None => {
                outln!("    brdfbake: {}", stats_line(&ch.brdfbake, dims));
                if let Some(s) = &ch.brdfbake_stored {
                    outln!("    brdfbake as stored: {}", stats_line(s, dims));
                }
            }
        }
        // (lines of texels are named, grouped into ranges, in the verdict)
        for f in ch
            .findings
            .iter()
            .filter(|f| !matches!(f, crate::engines::compare::Finding::Line { .. }))
        {
            outln!("    - {}", f.describe());
        }
    }
    outln!(
        "brdfbake's table {} its bound: max |error|/max(1, |exact|) <= {}",
        if c.brdfbake_within_bound() {
            "meets"
        } else {
            "MISSES"
        },
        num(c.brdfbake_bound)
    );
    Ok(())
}
