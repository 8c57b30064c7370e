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
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

pub fn run(a: ReportArgs) -> Result<(), CliError> {
    // the file first: a bad file fails fast, before any baking
    let shipped = match &a.filament_dfg {
        Some(p) => {
            let bytes = std::fs::read(p).map_err(|e| {
                CliError::env(format!("--filament-dfg {}: cannot read: {e}", p.display()))
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
    let presets = super::bake::resolve(&a.presets)?;
    let mut tables = Vec::new();
    for p in &presets {
        for t in &p.tables {
            let lut = crate::table::bake(&t.spec)
                .map_err(|e| CliError::input(format!("preset {}: {e}", p.name)))?;
            tables.push(ReportTable {
                preset: p.name.clone(),
                spec: t.spec.clone(),
                lut,
            });
        }
    }
    let comparison = shipped
        .as_ref()
        .map(|(label, d)| (label.as_str(), filament::compare(d, 1e-7)));
    let page = html(&tables, comparison.as_ref().map(|(label, c)| (*label, c)));
    let path = a.out.join("index.html");
    crate::pipeline::write_files(&vec![(path.clone(), page.into_bytes())])?;
    if !a.quiet {
        outln!("{} table(s) -> {}", tables.len(), path.display());
    }
    Ok(())
}
