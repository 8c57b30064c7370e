//! `brdfbake report [PRESET...] --out DIR`: one self-contained HTML page of the tables.

use super::CliError;
use crate::report::{filament, html, ReportTable};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// Preset names or files (default: every preset). Tables are baked in memory.
    pub presets: Vec<String>,
    /// Output directory; the page is written to DIR/index.html.
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// A DFG table as Filament ships it (the `dfg.inc` cmgen writes: half-float bits, GL
    /// row order, RG or RGB with cloth), compared with exact values in its own section.
    #[arg(long, value_name = "FILE")]
    pub filament_dfg: Option<PathBuf>,
    /// An engine's shipped table to compare, as PRESET=FILE (an engine preset and the
    /// engine's file, as for `brdfbake compare`); repeatable. Each gets a section with its
    /// errors and a heatmap per channel.
    #[arg(long, value_name = "PRESET=FILE")]
    pub compare: Vec<String>,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
    #[command(flatten)]
    pub guards: super::guards::Guards,
}

/// Largest `--filament-dfg` file read: a 4096² table with cloth written as `0xhhhh, ` (8
/// bytes a value, 3 values a texel) is 384 MiB; 512 MiB leaves room for line breaks.
const MAX_INC_BYTES: u64 = 512 << 20;

/// Integrand evaluations of one exact value of the comparison (a split sum and the cloth
/// channel at tolerance 1e-7, texel by texel: `resources`' dfg and cloth figures).
const EVALS_PER_COMPARED_TEXEL: f64 = 1_050.0;

pub fn run(a: ReportArgs) -> Result<(), CliError> {
    // the file first: a bad file fails fast, before any baking
    let shipped = match &a.filament_dfg {
        Some(p) => {
            let bytes = crate::input::read_regular(
                p,
                MAX_INC_BYTES,
                "a dfg.inc as Filament's cmgen writes it",
            )
            .map_err(|e| {
                let mut e = CliError::from(e);
                e.msg = format!("--filament-dfg: {}", e.msg);
                e
            })?;
            let text = String::from_utf8(bytes).map_err(|_| {
                CliError::input(format!(
                    "--filament-dfg {}: not a text file (expected a dfg.inc: half-float bit \
                     patterns such as 0x3c00, separated by commas)",
                    p.display()
                ))
            })?;
            let d = filament::parse_inc(&text)
                .map_err(|e| CliError::input(format!("--filament-dfg {}: {e}", p.display())))?;
            Some((p.display().to_string(), d))
        }
        None => None,
    };
    // the engine comparisons' presets and files, read before any baking
    let mut compares = Vec::new();
    for spec in &a.compare {
        let (name, file) = spec.split_once('=').ok_or_else(|| {
            CliError::input(format!(
                "--compare {spec}: give an engine preset and the engine's file as PRESET=FILE"
            ))
        })?;
        let preset = super::bake::resolve(&[name.to_string()])?.remove(0);
        let t = match preset.tables.as_slice() {
            [t] if t.shipped.is_some() => t.clone(),
            _ => {
                return Err(CliError::input(format!(
                    "--compare {spec}: {name} is not an engine preset of one table with a `shipped` description"
                )))
            }
        };
        let file = PathBuf::from(file);
        let bytes =
            crate::input::read_regular(&file, 1400 << 20, "a shipped table file").map_err(|e| {
                let mut e = CliError::from(e);
                e.msg = format!("--compare: {}", e.msg);
                e
            })?;
        compares.push((preset, t, file, bytes));
    }
    let presets = super::bake::resolve(&a.presets)?;
    // the tables as a bake of them in EXR would hold them, and the page: ~the PNG previews
    let est = crate::resources::estimate(
        &presets,
        Some(&[crate::preset::Format::Exr, crate::preset::Format::Png]),
    );
    let compared = shipped
        .as_ref()
        .map_or(0, |(_, d)| filament::exact_values(d));
    // each --compare bakes its table twice (the preset's and the exact reference, ~2x)
    let engine_presets: Vec<crate::preset::Preset> =
        compares.iter().map(|(p, ..)| p.clone()).collect();
    let engine_time = crate::resources::estimate_time(&engine_presets);
    let time = crate::resources::estimate_time(&presets)
        + crate::resources::time_of_evaluations(compared as f64 * EVALS_PER_COMPARED_TEXEL)
        + crate::resources::time_of_evaluations(3.0 * engine_time.evaluations);
    let deadline = a.guards.admit(&super::guards::Work {
        what: "this report",
        memory: est.peak() + compared as u64 * 48,
        memory_detail: format!(
            "{} texels baked in memory{}",
            est.texels,
            if compared > 0 {
                format!(", {compared} exact values of the shipped table")
            } else {
                String::new()
            }
        ),
        time,
        threads: rayon::current_num_threads(),
        smaller: "report fewer or smaller tables",
    })?;
    let mut tables = Vec::new();
    for p in &presets {
        for t in &p.tables {
            let opts = crate::table::BakeOptions {
                deadline: Some(&deadline),
                accept_error_estimate: t.accept_error_estimate,
            };
            // (an ltc table's fit error beside its texels, as the sidecar records it)
            let (lut, fit) = crate::table::bake_with_fit(&t.spec, &opts)
                .map_err(|e| super::bake_error(&p.name, e))?;
            tables.push(ReportTable {
                preset: p.name.clone(),
                spec: t.spec.clone(),
                lut,
                fit,
            });
        }
    }
    let comparison = match &shipped {
        Some((label, d)) => Some((
            label.as_str(),
            filament::compare_until(d, 1e-7, Some(&deadline))
                .ok_or_else(|| super::guards::stopped("this report", &deadline))?,
        )),
        None => None,
    };
    let mut engines = Vec::new();
    for (preset, t, file, bytes) in &compares {
        let c = crate::engines::compare_table(
            &preset.name,
            preset.source.as_ref(),
            t,
            bytes,
            &file.display().to_string(),
            Some(&deadline),
        )
        .map_err(|e| match e {
            crate::engines::CompareError::Input(m) => CliError::input(format!("--compare: {m}")),
            crate::engines::CompareError::Bake(e) => super::bake_error(&preset.name, e),
        })?;
        engines.push(crate::report::engines::EngineComparison {
            source: preset.source.clone(),
            comparison: c,
        });
    }
    let page = html(
        &tables,
        comparison.as_ref().map(|(label, c)| (*label, c)),
        &engines,
    );
    let path = a.out.join("index.html");
    crate::pipeline::write_files(&vec![(path.clone(), page.into_bytes())])?;
    if !a.quiet {
        outln!("{} table(s) -> {}", tables.len(), path.display());
    }
    Ok(())
}
