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
