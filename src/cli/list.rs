//! `brdfbake list`: presets and table kinds.

use super::CliError;
use crate::table::TableKind;

#[derive(clap::Args, Debug)]
pub struct ListArgs {}

pub fn run(_: ListArgs) -> Result<(), CliError> {
    outln!("Presets:");
    let presets = super::bake::resolve(&[])?;
    for p in &presets {
        let tables: Vec<String> = p
            .tables
            .iter()
            .map(|t| {
                let dims: Vec<String> = t.spec.axes.iter().map(|a| a.size.to_string()).collect();
                format!(
                    "{} ({} {})",
                    t.spec.name,
                    t.spec.kind.name(),
                    dims.join("x")
                )
            })
            .collect();
        outln!("  {:<20} {}", p.name, tables.join(", "));
    }
    outln!("\nEngine presets (baked and compared by name: brdfbake bake NAME, brdfbake compare NAME FILE):");
    for (n, t) in crate::presets::ENGINES {
        let p = crate::preset::parse(t, &format!("built-in preset {n}"), n)
            .map_err(|e| CliError::input(e.to_string()))?;
        let what = p
            .source
            .as_ref()
            .map_or(String::new(), |s| format!("{} {}", s.engine, s.table));
        let dims: Vec<String> = p
            .tables
            .iter()
            .map(|t| {
                t.stored_axes()
                    .iter()
                    .map(|a| a.size.to_string())
                    .collect::<Vec<_>>()
                    .join("x")
            })
            .collect();
        outln!("  {:<28} {} ({})", n, what, dims.join(", "));
    }
    outln!("\nTable kinds:");
    for k in TableKind::ALL.into_iter().chain(TableKind::CLASSIC) {
        outln!(
            "  {:<12} axes {:<40} {}",
            k.name(),
            k.axis_names().join(", "),
            k.description()
        );
    }
    Ok(())
}
