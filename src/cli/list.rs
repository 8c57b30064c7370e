//! `brdfbake list`: presets and table kinds, as text or one JSON document.

use super::CliError;
use crate::table::TableKind;
use serde_json::json;

#[derive(clap::Args, Debug)]
pub struct ListArgs {
    /// One JSON document (schema brdfbake.list/1) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// A table of a preset: name, kind and stored sizes.
fn table_doc(t: &crate::preset::PresetTable) -> serde_json::Value {
    json!({
        "name": t.spec.name,
        "kind": t.spec.kind.name(),
        "size": t.stored_axes().iter().map(|a| a.size).collect::<Vec<_>>(),
    })
}

fn dims(t: &serde_json::Value) -> String {
    t["size"]
        .as_array()
        .map(|s| {
            s.iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()
                .join("x")
        })
        .unwrap_or_default()
}

pub fn run(a: ListArgs) -> Result<(), CliError> {
    let presets = super::bake::resolve(&[])?;
    let defaults: Vec<serde_json::Value> = presets
        .iter()
        .map(|p| {
            json!({
                "name": p.name,
                "tables": p.tables.iter().map(table_doc).collect::<Vec<_>>(),
            })
        })
        .collect();
    let mut engines = Vec::new();
    for (n, t) in crate::presets::ENGINES {
        let p = crate::preset::parse(t, &format!("built-in preset {n}"), n)
            .map_err(|e| CliError::input(e.to_string()))?;
        engines.push(json!({
            "name": n,
            "engine": p.source.as_ref().map(|s| s.engine.clone()),
            "engine_table": p.source.as_ref().map(|s| s.table.clone()),
            "tables": p.tables.iter().map(table_doc).collect::<Vec<_>>(),
        }));
    }
    let kinds: Vec<serde_json::Value> = TableKind::ALL
        .into_iter()
        .chain(TableKind::CLASSIC)
        .map(|k| {
            json!({
                "name": k.name(),
                "axes": k.axis_names(),
                "description": k.description(),
            })
        })
        .collect();
    if a.json {
        let doc = json!({
            "schema": "brdfbake.list/1",
            "presets": defaults,
            "engine_presets": engines,
            "engines": crate::engines::select::engines()
                .into_iter()
                .map(|(k, v)| json!({"name": k, "presets": v}))
                .collect::<Vec<_>>(),
            "table_kinds": kinds,
        });
        outln!(
            "{}",
            serde_json::to_string_pretty(&doc).expect("serializable")
        );
        return Ok(());
    }
    outln!("Presets:");
    for p in &defaults {
        let tables: Vec<String> = p["tables"]
            .as_array()
            .expect("tables")
            .iter()
            .map(|t| {
                format!(
                    "{} ({} {})",
                    t["name"].as_str().unwrap_or(""),
                    t["kind"].as_str().unwrap_or(""),
                    dims(t)
                )
            })
            .collect();
        outln!(
            "  {:<20} {}",
            p["name"].as_str().unwrap_or(""),
            tables.join(", ")
        );
    }
    outln!("\nEngine presets (baked and compared by name: brdfbake bake NAME, brdfbake compare NAME FILE):");
    for e in &engines {
        let what = match (e["engine"].as_str(), e["engine_table"].as_str()) {
            (Some(en), Some(t)) => format!("{en} {t}"),
            _ => String::new(),
        };
        let sizes: Vec<String> = e["tables"]
            .as_array()
            .expect("tables")
            .iter()
            .map(dims)
            .collect();
        outln!(
            "  {:<28} {} ({})",
            e["name"].as_str().unwrap_or(""),
            what,
            sizes.join(", ")
        );
    }
    outln!("\nEngines (brdfbake bake --engine NAME bakes all of an engine's presets):");
    for (k, v) in crate::engines::select::engines() {
        outln!("  {:<12} {}", k, v.join(", "));
    }
    outln!("\nTable kinds:");
    for k in &kinds {
        let axes: Vec<&str> = k["axes"]
            .as_array()
            .expect("axes")
            .iter()
            .filter_map(|x| x.as_str())
            .collect();
        outln!(
            "  {:<12} axes {:<40} {}",
            k["name"].as_str().unwrap_or(""),
            axes.join(", "),
            k["description"].as_str().unwrap_or("")
        );
    }
    Ok(())
}
