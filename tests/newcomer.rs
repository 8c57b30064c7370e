//! A newcomer's first hour without a wrong turn (issue 36, section 3): each item a user met
//! is a test here — a mistyped preset gets the nearest name and sorted lists, `list --json`,
//! `bake --check`'s hint repeats the user's own arguments, negative numbers are values that
//! are then refused by flag, `verify` says what it checks and what decides its exit code,
//! `compare` names the file it expected and what it got, gives a verdict per channel in the
//! engine's channel names with degenerate slices named, and an LTC fit's bake prints the fit's
//! error instead of a quadrature estimate of 0. (The README's commands:
//! tests/readme_commands.rs; the toolchain: tests/toolchain.rs; the report and the test
//! command: tests/cli_tools.rs.)

#[path = "common/cli.rs"]
mod cli;

use cli::{assert_fails, run, INPUT};
use serde_json::Value;
use std::path::Path;

fn stdout(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn data(p: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/engines")
        .join(p)
        .display()
        .to_string()
}

#[test]
fn a_mistyped_preset_gets_the_nearest_name_and_sorted_lists() {
    let d = tempfile::tempdir().unwrap();
    let o = run(d.path(), &["bake", "filament-dgf"]);
    assert_fails(&o, INPUT, &["Did you mean `filament-dfg`?"], "a typo");
    let err = cli::stderr(&o);
    let list = err
        .split("Built-in presets: ")
        .nth(1)
        .and_then(|s| s.split(';').next())
        .expect("the built-in list");
    let names: Vec<&str> = list.split(", ").collect();
    let mut sorted = names.clone();
    sorted.sort_unstable();
    assert_eq!(names, sorted, "the list is sorted");
    // far from every name: no guess
    let o = run(d.path(), &["bake", "nothing-like-it"]);
    assert!(
        !cli::stderr(&o).contains("Did you mean"),
        "{}",
        cli::stderr(&o)
    );
}

#[test]
fn list_speaks_json() {
    let d = tempfile::tempdir().unwrap();
    let o = run(d.path(), &["list", "--json"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(doc["schema"], "brdfbake.list/1");
    let has = |k: &str, n: &str| doc[k].as_array().unwrap().iter().any(|p| p["name"] == n);
    assert!(has("presets", "filament-dfg") && has("engine_presets", "cycles-ggx-e"));
    assert!(has("table_kinds", "dfg"));
}

#[test]
fn check_hint_repeats_the_users_arguments() {
    let d = tempfile::tempdir().unwrap();
    let args = [
        "bake",
        "karis-envbrdf",
        "--out",
        "my luts",
        "--format",
        "exr",
        "-q",
    ];
    assert!(run(d.path(), &args).status.success());
    std::fs::remove_file(d.path().join("my luts/karis-envbrdf/envbrdf.exr")).unwrap();
    let o = run(
        d.path(),
        &[
            "bake",
            "karis-envbrdf",
            "--out",
            "my luts",
            "--format",
            "exr",
            "--check",
        ],
    );
    assert_fails(
        &o,
        1,
        &["run: brdfbake bake karis-envbrdf --out 'my luts' --format exr"],
        "a stale output",
    );
}

#[test]
fn negative_numbers_are_values_refused_by_flag() {
    let d = tempfile::tempdir().unwrap();
    let o = run(
        d.path(),
        &["eval", "d", "--cos-theta", "-0.5", "--roughness", "0.5"],
    );
    assert_fails(
        &o,
        INPUT,
        &["--cos-theta -0.5 is not a cosine"],
        "a negative cosine",
    );
    let o = run(
        d.path(),
        &[
            "eval",
            "e",
            "--cos-theta",
            "0.5",
            "--roughness",
            "0.5",
            "--f0",
            "-0.2",
        ],
    );
    assert_fails(
        &o,
        INPUT,
        &["--f0 -0.2 is not a reflectance"],
        "a negative F0",
    );
}

#[test]
fn verify_says_what_it_checks_and_what_decides_the_exit_code() {
    let d = tempfile::tempdir().unwrap();
    let o = run(d.path(), &["verify", "karis-envbrdf"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("checking the preset baked in memory (not the files in out/"),
        "{out}"
    );
    assert!(
        out.contains("exit 1 if a texel's error (relative above 1) exceeds 1.000e-6"),
        "{out}"
    );
    assert!(out.contains("not in the exit code"), "{out}");
    assert!(run(d.path(), &["bake", "karis-envbrdf", "-q"])
        .status
        .success());
    let o = run(
        d.path(),
        &["verify", "out/karis-envbrdf/envbrdf.exr", "--json"],
    );
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(doc["tables"][0]["checked"], "file");
    assert_eq!(doc["tables"][0]["threshold"], 1e-6);
    assert_eq!(doc["tables"][0]["lookups"]["in_exit_code"], false);
}

#[test]
fn compare_names_the_file_it_expected() {
    let d = tempfile::tempdir().unwrap();
    let o = run(
        d.path(),
        &["compare", "cycles-ggx-e", &data("gltf/lut_ggx.png")],
    );
    assert_fails(
        &o,
        INPUT,
        &[
            "cycles-ggx-e reads a text file holding the array table_ggx_E",
            "looks like a PNG image",
        ],
        "a PNG for a text table",
    );
    let o = run(
        d.path(),
        &["compare", "gltf-lut-ggx", &data("cycles/shader.tables")],
    );
    assert_fails(
        &o,
        INPUT,
        &[
            "gltf-lut-ggx reads a 3-channel PNG",
            "looks like Cycles' shader.tables",
        ],
        "Cycles' tables for a PNG",
    );
}

#[test]
fn compare_gives_verdicts_in_the_engines_names() {
    let d = tempfile::tempdir().unwrap();
    let o = run(
        d.path(),
        &["compare", "cycles-glass-e", &data("cycles/shader.tables")],
    );
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("left out of the verdicts: fresnel texel 0 (η = 1 + 2e-8, 256 texels)"),
        "{out}"
    );
    assert!(
        out.contains("verdict: ") && out.contains("its storage rounding (6 decimals"),
        "{out}"
    );
    assert!(
        out.contains("texel x = ") && !out.contains("fresnel=1e-8"),
        "{out}"
    );
    let o = run(
        d.path(),
        &[
            "compare",
            "gltf-lut-ggx",
            &data("gltf/lut_ggx.png"),
            "--json",
        ],
    );
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    let names: Vec<&str> = doc["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["A", "B"], "glTF's own channel names");
    for c in doc["channels"].as_array().unwrap() {
        assert_eq!(c["verdict"]["within_storage"], false, "{c}");
        assert!(c["verdict"]["ratio"].as_f64().unwrap() > 4.0, "{c}");
    }
    let o = run(
        d.path(),
        &["compare", "gltf-lut-ggx", &data("gltf/lut_ggx.png")],
    );
    assert!(stdout(&o).contains("  A (stored as R):"), "{}", stdout(&o));
}

#[test]
fn an_ltc_fit_prints_its_fit_error() {
    let d = tempfile::tempdir().unwrap();
    let o = run(d.path(), &["bake", "heitz-ltc"]);
    assert!(o.status.success(), "{}", cli::stderr(&o));
    let out = stdout(&o);
    let line = out
        .lines()
        .find(|l| l.starts_with("heitz-ltc/ltc_1:"))
        .expect("ltc_1");
    assert!(
        line.contains("LTC fit: the worst probe light's relative lit error"),
        "{line}"
    );
    assert!(!line.contains("est. max error 0.0e0"), "{line}");
}
