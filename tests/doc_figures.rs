//! Every figure the docs give about an engine's shipped table comes from `compare`: the
//! README's engine table and docs/engines.md's per-channel verdicts are rendered again here
//! from the comparisons of `tests/data/engines/manifest.json`, and must equal the docs'
//! blocks. A change in a preset, a shipped file or `compare` that moves a figure fails this
//! test until `cargo run --release --example engine_figures -- --write` regenerates the docs.

#[path = "common/engine_figures.rs"]
mod engine_figures;

#[test]
fn the_docs_engine_figures_are_comparisons() {
    let cs = engine_figures::comparisons();
    for (path, want) in engine_figures::generated_docs(&cs) {
        let have = std::fs::read_to_string(engine_figures::root().join(path)).unwrap();
        if have != want {
            let diff: Vec<String> = want
                .lines()
                .zip(have.lines())
                .filter(|(w, h)| w != h)
                .take(5)
                .map(|(w, h)| format!("  docs:      {h}\n  generated: {w}"))
                .collect();
            panic!(
                "{path}'s generated engine figures differ from `compare` (run `cargo run --release --example engine_figures -- --write`):\n{}",
                diff.join("\n")
            );
        }
    }
    for c in &cs {
        assert!(c.brdfbake_within_bound(), "{}: brdfbake misses its bound", c.preset);
    }
    // every table file kept as test data is compared, so none is left out of the figures
    let dir = engine_figures::root().join("tests/data/engines");
    let manifest = std::fs::read_to_string(dir.join("manifest.json")).unwrap();
    for engine in std::fs::read_dir(&dir).unwrap() {
        let engine = engine.unwrap().path();
        if !engine.is_dir() {
            continue;
        }
        for f in std::fs::read_dir(&engine).unwrap() {
            let f = f.unwrap().path();
            let name = f.file_name().unwrap().to_string_lossy().to_string();
            // (licences, and the LTC quotes tests/ltc_layouts.rs reads value by value)
            if name == "LICENSE" || name == "ltc_quotes.txt" {
                continue;
            }
            let rel = format!(
                "{}/{name}",
                engine.file_name().unwrap().to_string_lossy()
            );
            assert!(
                manifest.contains(&format!("\"file\": \"{rel}\"")),
                "tests/data/engines/{rel} is not compared in manifest.json"
            );
        }
    }
}
