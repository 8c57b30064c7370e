//! The generated engine tables of the docs: every comparison of `tests/data/engines/manifest.json`
//! run through the library's `compare`, rendered by `brdfbake::engines::figures`, and put
//! between the docs' markers. Shared by `tests/doc_figures.rs` (which checks the docs) and
//! `examples/engine_figures.rs` (which rewrites them).

#![allow(dead_code)]

use brdfbake::engines::{compare_table, figures, Comparison};
use std::path::{Path, PathBuf};

/// The repository's root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every comparison the manifest lists, in its order.
pub fn comparisons() -> Vec<Comparison> {
    use rayon::prelude::*;
    let data = root().join("tests/data/engines");
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(data.join("manifest.json")).unwrap()).unwrap();
    let entries: Vec<(String, String)> = manifest["compare"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| {
            (
                e["preset"].as_str().unwrap().to_string(),
                e["file"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    entries
        .par_iter()
        .map(|(name, file)| {
            let (_, text) = brdfbake::presets::ENGINES
                .iter()
                .find(|(n, _)| n == name)
                .unwrap_or_else(|| panic!("the manifest names {name}, not an engine preset"));
            let preset = brdfbake::preset::parse(text, name, name).unwrap();
            let t = &preset.tables[0];
            let bytes = std::fs::read(data.join(file)).unwrap();
            let shown = Path::new("tests/data/engines").join(file);
            compare_table(
                name,
                preset.source.as_ref(),
                t,
                &bytes,
                &shown.display().to_string(),
                None,
            )
            .unwrap_or_else(|e| panic!("compare {name} {file}: {e}"))
        })
        .collect()
}

/// The docs with their generated blocks as the comparisons give them: (path relative to
/// the root, text).
pub fn generated_docs(cs: &[Comparison]) -> Vec<(&'static str, String)> {
    let readme: String = std::iter::once(figures::README_HEADER.to_string())
        .chain(cs.iter().map(figures::readme_row))
        .map(|r| r + "\n")
        .collect();
    let detail: String = std::iter::once(figures::DETAIL_HEADER.to_string())
        .chain(cs.iter().flat_map(figures::detail_rows))
        .map(|r| r + "\n")
        .collect();
    let mut out = Vec::new();
    for (path, block, body) in [
        ("README.md", "engine-table", readme),
        ("docs/engines.md", "engine-verdicts", detail),
    ] {
        let text = std::fs::read_to_string(root().join(path)).unwrap();
        let new = figures::replace_block(&text, block, &body)
            .unwrap_or_else(|| panic!("{path} lacks the markers of the block {block}"));
        out.push((path, new));
    }
    out
}
