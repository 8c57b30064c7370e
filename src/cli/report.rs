//! `brdfbake report [PRESET...] --out DIR`: one self-contained HTML page of the tables.

use super::CliError;
use crate::report::{html, ReportTable};
use std::path::PathBuf;

#[derive(clap::Args, Debug)]
pub struct ReportArgs {
    /// Preset names or files (default: every preset). Tables are baked in memory.
    pub presets: Vec<String>,
    /// Output directory; the page is written to DIR/index.html.
    #[arg(long, default_value = "report")]
    pub out: PathBuf,
    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}

pub fn run(a: ReportArgs) -> Result<(), CliError> {
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
    let page = html(&tables);
    let path = a.out.join("index.html");
    crate::pipeline::write_files(&vec![(path.clone(), page.into_bytes())]).map_err(
        |e| match e {
            crate::pipeline::PipelineError::Input(m) => CliError::input(m),
            crate::pipeline::PipelineError::Environment(m) => CliError::env(m),
        },
    )?;
    if !a.quiet {
        println!("{} table(s) -> {}", tables.len(), path.display());
    }
    Ok(())
}
