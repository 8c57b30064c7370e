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
        assert!(
            c.brdfbake_within_bound(),
            "{}: brdfbake misses its bound",
            c.preset
        );
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
            let rel = format!("{}/{name}", engine.file_name().unwrap().to_string_lossy());
            assert!(
                manifest.contains(&format!("\"file\": \"{rel}\"")),
                "tests/data/engines/{rel} is not compared in manifest.json"
            );
        }
    }
}

/// BENCHMARKS.md's rows of the default presets (`scripts/bench.sh`, whose timings only a
/// benchmark run can give) also hold figures any bake reproduces: the integrand evaluations
/// and the largest error estimate of each preset's tables. Baked here, they must be the
/// figures printed there, so the table cannot outlive a change of the numerics; after one,
/// `scripts/bench.sh` gives the new table.
#[test]
fn the_benchmarks_deterministic_columns_are_the_bakes() {
    let text = std::fs::read_to_string(engine_figures::root().join("BENCHMARKS.md")).unwrap();
    for (name, preset_text) in brdfbake::presets::BUILTIN {
        let preset = brdfbake::preset::parse(preset_text, name, name).unwrap();
        let (mut evals, mut est) = (0u64, 0.0f64);
        for t in &preset.tables {
            let lut = brdfbake::table::bake(&t.spec).unwrap();
            evals += lut.evaluations;
            est = est.max(lut.error_estimate.iter().fold(0.0, |m: f64, e| m.max(*e)));
        }
        let row = text
            .lines()
            .find(|l| l.starts_with(&format!("| {name} | **whole process** |")))
            .unwrap_or_else(|| panic!("BENCHMARKS.md has no row of {name}"));
        let cols: Vec<&str> = row.split('|').map(str::trim).collect();
        // | preset | table | size | threads | wall | CPU | runs | evaluations | ev/s | est | ...
        assert_eq!(
            cols[8],
            evals.to_string(),
            "{name}: BENCHMARKS.md says {} evaluations, the bake makes {evals} (rerun scripts/bench.sh)",
            cols[8]
        );
        // (examples/bench.rs prints a closed form's 0 as "0")
        let want = if evals == 0 && est == 0.0 {
            "0".to_string()
        } else {
            format!("{est:.1e}")
        };
        assert_eq!(
            cols[10],
            want,
            "{name}: BENCHMARKS.md's est. max error differs from the bake's (rerun scripts/bench.sh)"
        );
    }
}
