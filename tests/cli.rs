//! End-to-end tests of the `brdfbake` binary: successful bakes and their outputs,
//! determinism across thread counts, `list`, every class of bad input (exit code, message,
//! nothing written) and the atomicity of a failed bake.
//!
//! Every bake runs with its working directory in a temporary directory, so the repository's
//! `presets/` is not seen and the built-in presets are the ones looked up by name.

#[path = "common/cli.rs"]
mod cli_support;
use cli_support::snapshot;

use serde_json::Value;
use std::ffi::OsString;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A small preset with one table of every kind (and several models, roughness quantities,
/// conventions and storages); bakes in well under a second.
const TINY: &str = r#"{
  "schema": "brdfbake.preset/1",
  "description": "tiny tables of every kind, for the CLI tests",
  "tables": [
    {
      "name": "dfg", "kind": "dfg", "layout": "filament", "cloth": true,
      "model": { "ndf": "ggx", "masking": "smith-height-correlated" },
      "axes": {
        "cos_theta_v": { "size": 6 },
        "roughness": { "size": 5, "quantity": "perceptual", "range": [0.1, 1], "convention": "endpoints" }
      }
    },
    {
      "name": "envbrdf", "kind": "dfg", "layout": "karis", "storage": "f16",
      "model": { "ndf": "beckmann", "masking": "smith-separable" },
      "axes": { "cos_theta_v": { "size": 4 }, "roughness": { "size": 4, "quantity": "cook-torrance-m" } }
    },
    {
      "name": "d", "kind": "ndf",
      "model": { "ndf": "blinn-phong" },
      "axes": {
        "cos_theta_h": { "size": 8, "range": [0, 1], "convention": "endpoints" },
        "roughness": { "size": 4, "quantity": "blinn-phong-exponent", "range": [1, 100] }
      }
    },
    {
      "name": "g1", "kind": "g1",
      "model": { "ndf": "gaussian" },
      "axes": { "cos_theta": { "size": 6 }, "roughness": { "size": 4, "quantity": "cook-torrance-m", "range": [0.05, 0.6] } }
    },
    {
      "name": "g2", "kind": "g2",
      "model": { "ndf": "ggx", "masking": "smith-height-correlated" },
      "axes": {
        "cos_theta_v": { "size": 4 }, "cos_theta_l": { "size": 5 },
        "roughness": { "size": 4, "quantity": "alpha" }
      }
    },
    {
      "name": "vgroove", "kind": "vgroove",
      "axes": { "n_dot_l": { "size": 4 }, "n_dot_h": { "size": 5 }, "n_dot_v": { "size": 6 } }
    },
    {
      "name": "albedo", "kind": "albedo", "tolerance": 1e-6,
      "model": {
        "ndf": "ggx", "masking": "smith-height-correlated",
        "fresnel": { "type": "dielectric", "eta": 1.5 }, "diffuse": 0.5
      },
      "axes": { "cos_theta_v": { "size": 5 }, "roughness": { "size": 4, "quantity": "alpha", "range": [0.05, 1] } }
    },
    {
      "name": "e-avg", "kind": "albedo-avg",
      "model": { "ndf": "charlie", "masking": "ashikhmin" },
      "axes": { "roughness": { "size": 4, "quantity": "perceptual" } }
    }
  ]
}
"#;

/// What each table of [`TINY`] must produce: (name, kind, axes (name, size, quantity),
/// channels).
type Expected = (
    &'static str,
    &'static str,
    &'static [(&'static str, usize, &'static str)],
    &'static [&'static str],
);
const TINY_TABLES: &[Expected] = &[
    (
        "dfg",
        "dfg",
        &[
            ("cos_theta_v", 6, "cosine"),
            ("roughness", 5, "roughness:perceptual"),
        ],
        &["R", "G", "B"],
    ),
    (
        "envbrdf",
        "dfg",
        &[
            ("cos_theta_v", 4, "cosine"),
            ("roughness", 4, "roughness:cook-torrance-m"),
        ],
        &["A", "B"],
    ),
    (
        "d",
        "ndf",
        &[
            ("cos_theta_h", 8, "cosine"),
            ("roughness", 4, "roughness:blinn-phong-exponent"),
        ],
        &["D"],
    ),
    (
        "g1",
        "g1",
        &[
            ("cos_theta", 6, "cosine"),
            ("roughness", 4, "roughness:cook-torrance-m"),
        ],
        &["G1"],
    ),
    (
        "g2",
        "g2",
        &[
            ("cos_theta_v", 4, "cosine"),
            ("cos_theta_l", 5, "cosine"),
            ("roughness", 4, "roughness:alpha"),
        ],
        &["G2"],
    ),
    (
        "vgroove",
        "vgroove",
        &[
            ("n_dot_l", 4, "cosine"),
            ("n_dot_h", 5, "cosine"),
            ("n_dot_v", 6, "cosine"),
        ],
        &["G", "realizable"],
    ),
    (
        "albedo",
        "albedo",
        &[
            ("cos_theta_v", 5, "cosine"),
            ("roughness", 4, "roughness:alpha"),
        ],
        &["E"],
    ),
    (
        "e-avg",
        "albedo-avg",
        &[("roughness", 4, "roughness:perceptual")],
        &["E_avg"],
    ),
];

/// The OpenEXR magic number.
const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

// ---------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------

/// Runs the binary in `cwd` with `args`.
fn run<I, S>(cwd: &Path, args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: Into<OsString>,
{
    let args: Vec<OsString> = args.into_iter().map(Into::into).collect();
    Command::new(env!("CARGO_BIN_EXE_brdfbake"))
        .args(&args)
        .current_dir(cwd)
        .env_remove("RAYON_NUM_THREADS")
        .output()
        .unwrap_or_else(|e| panic!("cannot run brdfbake {args:?}: {e}"))
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Asserts a successful run, showing its output otherwise.
fn assert_ok(o: &Output, what: &str) {
    assert!(
        o.status.code() == Some(0),
        "{what}: expected exit 0, got {:?}\nstdout:\n{}\nstderr:\n{}",
        o.status.code(),
        stdout(o),
        stderr(o)
    );
}

/// Asserts a failed run: the exit code, `error:` first, every expected substring, no panic.
fn assert_fails(o: &Output, code: i32, expect: &[&str], what: &str) {
    let err = stderr(o);
    assert_eq!(
        o.status.code(),
        Some(code),
        "{what}: wrong exit code\nstdout:\n{}\nstderr:\n{err}",
        stdout(o)
    );
    assert!(
        err.starts_with("error:"),
        "{what}: stderr does not start with \"error:\":\n{err}"
    );
    assert!(
        !err.contains("panicked"),
        "{what}: the binary panicked:\n{err}"
    );
    for s in expect {
        assert!(
            err.contains(s),
            "{what}: stderr does not contain {s:?}:\n{err}"
        );
    }
}

/// Asserts that no file (of any kind) exists under `dir`.
fn assert_no_files(dir: &Path, what: &str) {
    let files: Vec<PathBuf> = snapshot(dir).into_keys().collect();
    assert!(
        files.is_empty(),
        "{what}: files were written under {}: {files:?}",
        dir.display()
    );
}

/// Asserts that no temporary file (`.<name>.tmp-…`) remains under `dir`.
fn assert_no_temp_files(dir: &Path, what: &str) {
    let temps: Vec<PathBuf> = snapshot(dir)
        .into_keys()
        .filter(|p| p.to_string_lossy().contains(".tmp"))
        .collect();
    assert!(temps.is_empty(), "{what}: temporary files left: {temps:?}");
}

/// Writes `text` to `dir/name` and returns the path.
fn write_preset(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    fs::write(&p, text).unwrap();
    p
}

fn fixture_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_input")
}

/// A two-table preset: table `a` (g1) whose `cos_theta` size is `n` (change it to change
/// `a`'s bytes), then `second`, the JSON of table `b`.
fn two_tables(n: usize, second: &str) -> String {
    format!(
        r#"{{"schema": "brdfbake.preset/1", "tables": [
  {{"name": "a", "kind": "g1", "model": {{"ndf": "ggx"}},
    "axes": {{"cos_theta": {{"size": {n}}}, "roughness": {{"size": 4, "quantity": "alpha"}}}}}},
  {second}
]}}"#
    )
}

const SECOND_OK: &str = r#"{"name": "b", "kind": "ndf", "model": {"ndf": "beckmann"},
    "axes": {"cos_theta_h": {"size": 4}, "roughness": {"size": 4, "quantity": "alpha"}}}"#;

// ---------------------------------------------------------------------------------------
// 1. A successful bake and its outputs
// ---------------------------------------------------------------------------------------

/// The coordinate of texel `i` per the documented conventions.
fn expected_coord(convention: &str, [lo, hi]: [f64; 2], n: usize, i: usize) -> f64 {
    match convention {
        "centers" => lo + (hi - lo) * (i as f64 + 0.5) / n as f64,
        "endpoints" => lo + (hi - lo) * i as f64 / (n - 1) as f64,
        c => panic!("unknown convention {c}"),
    }
}

fn as_f64s(v: &Value, what: &str) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("{what} is not an array: {v}"))
        .iter()
        .map(|x| {
            x.as_f64()
                .unwrap_or_else(|| panic!("{what} holds a non-number {x}"))
        })
        .collect()
}

#[test]
fn bake_writes_exr_and_sidecar_per_table() {
    let work = tempfile::tempdir().unwrap();
    let preset = write_preset(work.path(), "tiny-lut.json", TINY);
    let out = work.path().join("luts");
    let args: Vec<OsString> = vec![
        "bake".into(),
        preset.into(),
        "--out".into(),
        out.clone().into(),
        "--threads".into(),
        "2".into(),
    ];
    let o = run(work.path(), args);
    assert_ok(&o, "bake tiny-lut.json");
    assert!(stderr(&o).is_empty(), "stderr: {}", stderr(&o));

    // Exactly <out>/<preset-stem>/<table>.{exr,json} for every table.
    let files = snapshot(&out);
    let mut want: Vec<PathBuf> = TINY_TABLES
        .iter()
        .flat_map(|(n, ..)| {
            [
                Path::new("tiny-lut").join(format!("{n}.exr")),
                Path::new("tiny-lut").join(format!("{n}.json")),
            ]
        })
        .collect();
    want.sort();
    assert_eq!(files.keys().cloned().collect::<Vec<_>>(), want);

    let report = stdout(&o);
    for &(name, kind, axes, channels) in TINY_TABLES {
        let what = format!("table {name}");
        assert!(
            report.contains(&format!("tiny-lut/{name}:")),
            "{what}: not reported on stdout:\n{report}"
        );
        let exr = &files[&Path::new("tiny-lut").join(format!("{name}.exr"))];
        assert!(exr.starts_with(&EXR_MAGIC), "{what}: not an EXR file");
        let text = &files[&Path::new("tiny-lut").join(format!("{name}.json"))];
        let text = std::str::from_utf8(text).expect("sidecar is UTF-8");
        assert!(
            text.ends_with('\n'),
            "{what}: sidecar lacks a final newline"
        );
        let j: Value = serde_json::from_str(text)
            .unwrap_or_else(|e| panic!("{what}: sidecar is not JSON: {e}"));

        assert_eq!(j["schema"], "brdfbake.lut/1", "{what}");
        assert_eq!(j["generator"]["name"], "brdfbake", "{what}");
        assert_eq!(j["preset"], "tiny-lut", "{what}");
        assert_eq!(j["table"]["name"], name, "{what}");
        assert_eq!(j["table"]["kind"], kind, "{what}");
        assert_eq!(j["table"]["dimensions"], axes.len(), "{what}");
        let sizes: Vec<usize> = axes.iter().map(|a| a.1).collect();
        assert_eq!(j["table"]["size"], serde_json::json!(sizes), "{what}");
        assert_eq!(j["files"]["exr"], format!("{name}.exr"), "{what}");

        let hash = j["input_hash"].as_str().expect("input_hash is a string");
        let hex = hash
            .strip_prefix("sha256:")
            .unwrap_or_else(|| panic!("{what}: input_hash {hash:?} lacks sha256:"));
        assert!(
            hex.len() == 64 && hex.bytes().all(|b| b.is_ascii_hexdigit()),
            "{what}: input_hash {hash:?}"
        );

        let jaxes = j["axes"].as_array().expect("axes is an array");
        assert_eq!(jaxes.len(), axes.len(), "{what}");
        for (k, (ja, &(an, size, quantity))) in jaxes.iter().zip(axes).enumerate() {
            let what = format!("{what} axis {k} ({an})");
            assert_eq!(ja["name"], an, "{what}");
            assert_eq!(ja["size"], size, "{what}");
            assert_eq!(ja["quantity"], quantity, "{what}");
            assert_eq!(ja["texture_axis"], ["u", "v", "w (slice)"][k], "{what}");
            let range = as_f64s(&ja["range"], "range");
            let range = [range[0], range[1]];
            let conv = ja["convention"].as_str().expect("convention");
            let coords = as_f64s(&ja["coordinates"], "coordinates");
            assert_eq!(coords.len(), size, "{what}: coordinates");
            for (i, &c) in coords.iter().enumerate() {
                let e = expected_coord(conv, range, size, i);
                assert!(
                    (c - e).abs() <= 1e-12 * e.abs().max(1.0),
                    "{what}: texel {i} at {c}, expected {e}"
                );
            }
            if quantity.starts_with("roughness:") {
                let alpha = as_f64s(&ja["alpha"], "alpha");
                assert_eq!(alpha.len(), size, "{what}: alpha");
                assert!(alpha.iter().all(|&a| a > 0.0), "{what}: alpha {alpha:?}");
                if quantity == "roughness:perceptual" {
                    for (a, c) in alpha.iter().zip(&coords) {
                        assert!((a - c * c).abs() <= 1e-15, "{what}: alpha {a} for r = {c}");
                    }
                }
            } else {
                assert!(ja.get("alpha").is_none(), "{what}: a cosine axis has alpha");
            }
        }

        let jch: Vec<&str> = j["channels"]
            .as_array()
            .expect("channels")
            .iter()
            .map(|c| c["name"].as_str().expect("channel name"))
            .collect();
        assert_eq!(jch, channels, "{what}: channels");
        for c in channels {
            let e = j["quadrature"]["estimated_max_error"][c]
                .as_f64()
                .unwrap_or_else(|| panic!("{what}: no error estimate for channel {c}"));
            assert!(e.is_finite() && e >= 0.0, "{what}: error estimate {e}");
        }
    }

    // The envbrdf table asked for f16 storage, the others default to f32.
    let j: Value =
        serde_json::from_slice(&files[&Path::new("tiny-lut").join("envbrdf.json")]).unwrap();
    assert_eq!(j["storage"]["texel_type"], "f16");
    let j: Value = serde_json::from_slice(&files[&Path::new("tiny-lut").join("dfg.json")]).unwrap();
    assert_eq!(j["storage"]["texel_type"], "f32");
}

/// A preset name (no path) from a working directory without `presets/` resolves to the
/// built-in copy; `--quiet` prints nothing.
#[test]
fn bake_builtin_preset_by_name() {
    let work = tempfile::tempdir().unwrap();
    let o = run(
        work.path(),
        [
            "bake",
            "gaussian-ndf",
            "--out",
            "o",
            "--quiet",
            "--threads",
            "2",
        ],
    );
    assert_ok(&o, "bake gaussian-ndf");
    assert!(stdout(&o).is_empty(), "--quiet printed: {}", stdout(&o));
    let files: Vec<PathBuf> = snapshot(&work.path().join("o")).into_keys().collect();
    let want: Vec<PathBuf> = ["d.exr", "d.json", "g1.exr", "g1.json"]
        .iter()
        .map(|f| Path::new("gaussian-ndf").join(f))
        .collect();
    assert_eq!(files, want);
}

/// A name is looked up in `presets/` of the working directory before the built-in presets.
#[test]
fn bake_local_preset_by_name() {
    let work = tempfile::tempdir().unwrap();
    fs::create_dir(work.path().join("presets")).unwrap();
    write_preset(
        &work.path().join("presets"),
        "mine.json",
        &two_tables(4, SECOND_OK),
    );
    let o = run(work.path(), ["bake", "mine", "--out", "o", "-q"]);
    assert_ok(&o, "bake mine");
    assert_eq!(
        snapshot(&work.path().join("o"))
            .into_keys()
            .collect::<Vec<_>>(),
        ["mine/a.exr", "mine/a.json", "mine/b.exr", "mine/b.json"]
            .iter()
            .map(PathBuf::from)
            .collect::<Vec<_>>()
    );
}

// ---------------------------------------------------------------------------------------
// 2. Determinism
// ---------------------------------------------------------------------------------------

#[test]
fn outputs_are_identical_for_any_thread_count() {
    let work = tempfile::tempdir().unwrap();
    write_preset(work.path(), "tiny-lut.json", TINY);
    let mut snaps = Vec::new();
    for threads in ["1", "2", "8"] {
        let out = format!("out-{threads}");
        let o = run(
            work.path(),
            [
                "bake",
                "tiny-lut.json",
                "--out",
                &out,
                "--threads",
                threads,
                "-q",
            ],
        );
        assert_ok(&o, &format!("bake --threads {threads}"));
        let snap = snapshot(&work.path().join(&out));
        assert_eq!(snap.len(), 2 * TINY_TABLES.len(), "--threads {threads}");
        snaps.push((threads, snap));
    }
    // Baking again over existing outputs gives the same bytes too.
    let o = run(
        work.path(),
        [
            "bake",
            "tiny-lut.json",
            "--out",
            "out-1",
            "--threads",
            "2",
            "-q",
        ],
    );
    assert_ok(&o, "second bake into out-1");
    snaps.push(("2 (over out-1)", snapshot(&work.path().join("out-1"))));

    let (t0, first) = &snaps[0];
    for (t, snap) in &snaps[1..] {
        assert_eq!(
            first.keys().collect::<Vec<_>>(),
            snap.keys().collect::<Vec<_>>(),
            "file sets differ: --threads {t0} vs {t}"
        );
        for (path, bytes) in first {
            assert!(
                &snap[path] == bytes,
                "{} differs between --threads {t0} and --threads {t}",
                path.display()
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// 3. list
// ---------------------------------------------------------------------------------------

const BUILTIN: [&str; 6] = [
    "filament-dfg",
    "karis-envbrdf",
    "cook-torrance-1982",
    "gaussian-ndf",
    "smith-g",
    "energy-albedo",
];
const KINDS: [&str; 7] = ["ndf", "g1", "g2", "vgroove", "albedo", "albedo-avg", "dfg"];

#[test]
fn list_shows_builtin_presets_and_table_kinds() {
    let work = tempfile::tempdir().unwrap();
    let o = run(work.path(), ["list"]);
    assert_ok(&o, "list");
    let text = stdout(&o);
    let (presets, kinds) = text
        .split_once("Table kinds:")
        .unwrap_or_else(|| panic!("no \"Table kinds:\" section:\n{text}"));
    for p in BUILTIN {
        assert!(
            presets.lines().any(|l| l.trim_start().starts_with(p)),
            "preset {p} not listed:\n{text}"
        );
    }
    for k in KINDS {
        assert!(
            kinds
                .lines()
                .any(|l| l.split_whitespace().next() == Some(k)),
            "table kind {k} not listed:\n{text}"
        );
    }
    assert!(
        kinds.contains("cos_theta_v, cos_theta_l, roughness"),
        "{text}"
    );
    // A few of the tables of the built-in presets, with their sizes.
    assert!(presets.contains("dfg (dfg 128x128)"), "{text}");
    assert!(presets.contains("envbrdf (dfg 128x128)"), "{text}");
}

/// With a `presets/` directory in the working directory, `list` shows its presets instead.
#[test]
fn list_shows_local_presets() {
    let work = tempfile::tempdir().unwrap();
    fs::create_dir(work.path().join("presets")).unwrap();
    write_preset(
        &work.path().join("presets"),
        "mine.json",
        &two_tables(4, SECOND_OK),
    );
    let o = run(work.path(), ["list"]);
    assert_ok(&o, "list");
    let text = stdout(&o);
    assert!(text.contains("mine"), "{text}");
    assert!(text.contains("a (g1 4x4), b (ndf 4x4)"), "{text}");
    // the local presets replace the defaults (engine presets, built in, are listed below)
    let defaults = text.split("Engine presets").next().unwrap();
    assert!(!defaults.contains("filament-dfg"), "{text}");
}

// ---------------------------------------------------------------------------------------
// 4. Bad input
// ---------------------------------------------------------------------------------------

/// Exit code for bad input.
const INPUT: i32 = 2;
/// Exit code for a failure of the environment.
const ENV: i32 = 1;

/// Each fixture in `tests/bad_input/`, the exit code and what stderr must contain (the field
/// path and/or what is accepted). The message must also name the file.
const FIXTURES: &[(&str, i32, &[&str])] = &[
    // classic-albedo and classic-albedo-aniso tables (tests/classic_tables.rs)
    (
        "classic-missing-model.json",
        INPUT,
        &[
            "tables[0]",
            "model.classic is required",
            "ward-gmd, ashikhmin-shirley",
        ],
    ),
    (
        "classic-with-ndf.json",
        INPUT,
        &["tables[0]", "model.ndf must be omitted", "classic-albedo"],
    ),
    (
        "classic-ward-exponent.json",
        INPUT,
        &[
            "axes.roughness.quantity must be \"alpha\"",
            "ward",
            "got \"exponent\"",
        ],
    ),
    (
        "classic-aniso-phong.json",
        INPUT,
        &[
            "needs an anisotropic model",
            "ward-gmd or ashikhmin-shirley",
            "modified-phong",
        ],
    ),
    (
        "classic-unknown-type.json",
        INPUT,
        &[
            "tables[0].model.classic.type",
            "torrance-sparrow",
            "`lafortune`",
        ],
    ),
    (
        "classic-anisotropy-range.json",
        INPUT,
        &["axes.anisotropy.range must lie within [0, 1]", "[0, 2]"],
    ),
    (
        "classic-anisotropy-quantity.json",
        INPUT,
        &["tables[0].axes.anisotropy.quantity", "takes no quantity"],
    ),
    (
        "classic-exponent-negative.json",
        INPUT,
        &[
            "axes.roughness: texel 0 is at -1",
            "[0, 100000]",
            "ashikhmin-shirley",
        ],
    ),
    (
        "classic-on-albedo.json",
        INPUT,
        &["model.classic applies to classic-albedo", "not albedo"],
    ),
    (
        "classic-weight-above-1.json",
        INPUT,
        &["model.classic.rho_s must be a weight in [0, 1]", "1.5"],
    ),
    (
        "classic-lafortune-cx-cy.json",
        INPUT,
        &["cx (-1.2) and cy (-0.8) must be equal", "classic-albedo"],
    ),
    (
        "invalid-json.json",
        INPUT,
        &["invalid JSON", "line 5, column 36", "key must be a string"],
    ),
    (
        "empty-file.json",
        INPUT,
        &["invalid JSON", "line 1, column 0", "EOF"],
    ),
    ("missing-tables.json", INPUT, &["missing field `tables`"]),
    ("non-utf8.json", INPUT, &["not UTF-8", "offset 56"]),
    (
        "wrong-schema.json",
        INPUT,
        &[
            "schema: expected \"brdfbake.preset/1\"",
            "brdfbake.preset/2",
        ],
    ),
    (
        "unknown-kind.json",
        INPUT,
        &["tables[0].kind", "`brdf`", "`albedo-avg`", "`dfg`"],
    ),
    (
        "unknown-ndf.json",
        INPUT,
        &["tables[0].model.ndf", "`ggxx`", "`beckmann`", "`ggx`"],
    ),
    (
        "unknown-masking.json",
        INPUT,
        &[
            "tables[0].model.masking",
            "`smith`",
            "`smith-height-correlated`",
        ],
    ),
    (
        "unknown-fresnel.json",
        INPUT,
        &["tables[0].model.fresnel.type", "`fresnel`", "`schlick`"],
    ),
    (
        "unknown-field.json",
        INPUT,
        &["tables[0]", "unknown field `tolerence`", "`tolerance`"],
    ),
    (
        "unknown-format.json",
        INPUT,
        &["tables[0].formats[0]", "`tiff`", "`exr`"],
    ),
    (
        "duplicate-key.json",
        INPUT,
        &["tables[0]", "duplicate field `layout`"],
    ),
    (
        "missing-quantity.json",
        INPUT,
        &[
            "tables[0].axes.roughness.quantity",
            "is required",
            "alpha, perceptual, cook-torrance-m, blinn-phong-exponent",
        ],
    ),
    (
        "quantity-not-for-ndf.json",
        INPUT,
        &[
            "tables[0]",
            "axes.roughness.quantity \"cook-torrance-m\"",
            "ggx",
            "accepted: alpha, perceptual",
        ],
    ),
    (
        "quantity-on-cosine.json",
        INPUT,
        &[
            "tables[0].axes.cos_theta.quantity",
            "only the roughness axis",
        ],
    ),
    (
        "alpha-zero-endpoints.json",
        INPUT,
        &[
            "tables[0]",
            "axes.roughness",
            "texel 0",
            "alpha = 0",
            "Dirac delta",
            "centers",
        ],
    ),
    (
        "blinn-phong-alpha-above-1.json",
        INPUT,
        &[
            "tables[0]",
            "axes.roughness",
            "blinn-phong",
            "must lie within [0, 1]",
        ],
    ),
    (
        "dfg-cosine-zero.json",
        INPUT,
        &["tables[0]", "axes.cos_theta_v", "cosine 0", "centers"],
    ),
    (
        "negative-size.json",
        INPUT,
        &["tables[0].axes.cos_theta_v.size", "-4"],
    ),
    (
        "zero-size.json",
        INPUT,
        &["tables[0]", "axes.cos_theta_v.size", "1..=4096", "got 0"],
    ),
    (
        "size-1e9.json",
        INPUT,
        &[
            "tables[0]",
            "axes.cos_theta_v.size",
            "1..=4096",
            "1000000000",
        ],
    ),
    (
        "size-1e9-float.json",
        INPUT,
        &["tables[0].axes.cos_theta_v.size", "floating point"],
    ),
    (
        "size-100000.json",
        INPUT,
        &["tables[0]", "axes.roughness.size", "1..=4096", "100000"],
    ),
    (
        "size-as-string.json",
        INPUT,
        &["tables[0].axes.cos_theta.size", "string \"4\""],
    ),
    (
        "too-many-texels.json",
        INPUT,
        &["tables[0]", "67108864 texels", "16777216"],
    ),
    (
        "range-reversed.json",
        INPUT,
        &["tables[0]", "axes.cos_theta.range", "lo < hi", "[1, 0]"],
    ),
    (
        "cosine-beyond-1.json",
        INPUT,
        &["tables[0]", "axes.cos_theta.range", "within [0, 1]", "1.5"],
    ),
    (
        "nan-string.json",
        INPUT,
        &["tables[0].axes.roughness.range[1]", "string \"NaN\""],
    ),
    // serde_json cannot name the field of an out-of-range number; line and column it can.
    (
        "huge-number.json",
        INPUT,
        &["line 7, column", "number out of range"],
    ),
    (
        "extra-axis.json",
        INPUT,
        &[
            "tables[0].axes.cos_theta_v",
            "not an axis of a g1 table",
            "cos_theta, roughness",
        ],
    ),
    (
        "missing-axis.json",
        INPUT,
        &[
            "tables[0].axes.cos_theta",
            "is required",
            "cos_theta, roughness",
        ],
    ),
    (
        "fresnel-in-dfg.json",
        INPUT,
        &["tables[0]", "model.fresnel must be none", "dfg"],
    ),
    (
        "schlick-f0-2.json",
        INPUT,
        &["tables[0]", "model.fresnel.f0", "[0, 1]", "got 2"],
    ),
    (
        "diffuse-weight-2.json",
        INPUT,
        &["tables[0]", "model.diffuse", "[0, 1]", "got 2"],
    ),
    (
        "g2-vgroove.json",
        INPUT,
        &[
            "tables[0]",
            "model.masking \"v-groove\"",
            "accepts smith-separable, smith-height-correlated, ashikhmin",
            "vgroove",
        ],
    ),
    (
        "smith-charlie.json",
        INPUT,
        &["tables[0]", "smith masking of the charlie NDF", "ashikhmin"],
    ),
    (
        "dfg-charlie-none.json",
        INPUT,
        &[
            "tables[0]",
            "\"none\" masking of the charlie NDF",
            "use masking ashikhmin",
        ],
    ),
    (
        "g1-charlie.json",
        INPUT,
        &["tables[0]", "charlie", "ashikhmin"],
    ),
    (
        "dfg-missing-layout.json",
        INPUT,
        &["tables[0]", "layout \"karis\" or \"filament\""],
    ),
    (
        "cloth-alpha-min-without-cloth.json",
        INPUT,
        &["tables[0]", "cloth_alpha_min", "\"cloth\": true"],
    ),
    (
        "layout-on-g1.json",
        INPUT,
        &["tables[0]", "layout and cloth apply to dfg tables only"],
    ),
    (
        "duplicate-table-name.json",
        INPUT,
        &["tables[1].name", "\"t\"", "two tables"],
    ),
    (
        "bad-table-name.json",
        INPUT,
        &["tables[0].name", "\"../x\"", "a-z, A-Z, 0-9"],
    ),
    (
        "empty-tables.json",
        INPUT,
        &["tables", "at least one table"],
    ),
    (
        "empty-formats.json",
        INPUT,
        &["tables[0].formats", "at least one format", "exr"],
    ),
    (
        "tolerance-0.json",
        INPUT,
        &["tables[0]", "tolerance", "[1e-12, 1e-2]", "got 0"],
    ),
    (
        "second-table-invalid.json",
        INPUT,
        &["tables[1]", "axes.roughness", "must lie within [0, 1]"],
    ),
    // once known bugs: serde's derived structs accepted arrays for objects
    (
        "top-level-array.json",
        INPUT,
        &["(top level)", "must be a JSON object", "got an array"],
    ),
    (
        "array-form.json",
        INPUT,
        &["(top level)", "must be a JSON object", "got an array"],
    ),
    // a roughness axis spans alpha in [0, 1] (Ndf::new's [MIN_ALPHA, MAX_ALPHA] is wider)
    (
        "alpha-above-max.json",
        INPUT,
        &[
            "tables[0]",
            "axes.roughness",
            "within [0, 1]",
            "got [1, 200]",
        ],
    ),
    (
        "alpha-below-min.json",
        INPUT,
        &[
            "tables[0]",
            "axes.roughness",
            "texel 0",
            "[1e-9, 100]",
            "got 1e-12",
        ],
    ),
    (
        "negative-tolerance.json",
        INPUT,
        &["tables[0]", "tolerance", "[1e-12, 1e-2]", "got -1e-6"],
    ),
    (
        "axes-as-string.json",
        INPUT,
        &["tables[0].axes", "must be a JSON object", "got a string"],
    ),
    (
        "name-null.json",
        INPUT,
        &["tables[0].name", "is null", "leave an optional field out"],
    ),
    (
        "eta-negative.json",
        INPUT,
        &["tables[0]", "model.fresnel.eta", "(0, 100]", "got -1.5"],
    ),
    (
        "size-overflow-u64.json",
        INPUT,
        &["tables[0].axes.cos_theta.size", "expected usize"],
    ),
    (
        "range-one-element.json",
        INPUT,
        &[
            "tables[0].axes.cos_theta.range",
            "must be two numbers [lo, hi], got 1 numbers",
        ],
    ),
    (
        "scale-negative.json",
        INPUT,
        &["tables[0].scale", "(0, 1e30]", "got -2"],
    ),
    (
        "engine-unknown.json",
        INPUT,
        &[
            "tables[0].engine",
            "unknown variant `three`",
            "threejs",
            "blender",
        ],
    ),
    (
        "engine-number.json",
        INPUT,
        &["tables[0].engine", "accepted names", "got a number"],
    ),
    (
        "deeply-nested.json",
        INPUT,
        &["invalid JSON", "line 1", "recursion limit exceeded"],
    ),
    ("bom.json", INPUT, &["byte order mark", "without BOM"]),
];

/// Runs one bad-input case in a fresh working directory: `args` gets the working directory
/// and the output directory (which does not exist).
fn check_case(
    name: &str,
    code: i32,
    expect: &[&str],
    args: &dyn Fn(&Path, &Path) -> Vec<OsString>,
) {
    let work = tempfile::tempdir().unwrap();
    let out = work.path().join("out");
    let args = args(work.path(), &out);
    let o = run(work.path(), &args);
    assert_fails(&o, code, expect, &format!("{name} ({args:?})"));
    assert_no_files(&out, name);
}

fn fixture_args(file: &str) -> impl Fn(&Path, &Path) -> Vec<OsString> + '_ {
    move |_, out| {
        vec![
            "bake".into(),
            fixture_dir().join(file).into(),
            "--out".into(),
            out.into(),
        ]
    }
}

#[test]
fn bad_input_fixtures() {
    // Every fixture has an expectation and every expectation a fixture.
    let mut on_disk: Vec<String> = fs::read_dir(fixture_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json"))
        .collect();
    on_disk.sort();
    let mut listed: Vec<String> = FIXTURES.iter().map(|c| c.0).map(String::from).collect();
    listed.sort();
    assert_eq!(
        on_disk, listed,
        "tests/bad_input/*.json vs the FIXTURES table"
    );

    for &(file, code, expect) in FIXTURES {
        // The message names the file it is about.
        let mut all = expect.to_vec();
        all.push(file);
        check_case(file, code, &all, &fixture_args(file));
    }
}

type ArgsFn = fn(&Path, &Path) -> Vec<OsString>;

fn os(v: &[&str]) -> Vec<OsString> {
    v.iter().map(OsString::from).collect()
}

/// A valid tiny preset `good.json` in `work`; returns `bake good.json --out <out>`.
fn good_bake(work: &Path, out: &Path) -> Vec<OsString> {
    write_preset(work, "good.json", &two_tables(4, SECOND_OK));
    let mut v = os(&["bake", "good.json", "--out"]);
    v.push(out.into());
    v
}

/// Argument sets and working-directory setups that must fail: (name, code, stderr must
/// contain, setup returning the arguments).
const ARG_CASES: &[(&str, i32, &[&str], ArgsFn)] = &[
    (
        "preset path is a directory",
        INPUT,
        &["bad_input", "is a directory; give a preset .json file"],
        |_, out| {
            let mut v = os(&["bake"]);
            v.push(fixture_dir().into());
            v.extend(os(&["--out"]));
            v.push(out.into());
            v
        },
    ),
    (
        "missing preset file",
        INPUT,
        &["nope/missing.json", "no such preset file"],
        |_, out| {
            let mut v = os(&["bake", "nope/missing.json", "--out"]);
            v.push(out.into());
            v
        },
    ),
    (
        "missing preset file, bare name",
        INPUT,
        &["missing.json", "no such preset file"],
        |_, out| {
            let mut v = os(&["bake", "missing.json", "--out"]);
            v.push(out.into());
            v
        },
    ),
    (
        "unknown preset name",
        INPUT,
        &[
            "unknown preset \"no-such-preset\"",
            "Built-in presets:",
            "filament-dfg",
            "smith-g",
        ],
        |_, out| {
            let mut v = os(&["bake", "no-such-preset", "--out"]);
            v.push(out.into());
            v
        },
    ),
    (
        "preset named twice",
        INPUT,
        &["\"gaussian-ndf\" is named twice"],
        |_, out| {
            let mut v = os(&["bake", "gaussian-ndf", "gaussian-ndf", "--out"]);
            v.push(out.into());
            v
        },
    ),
    (
        "good then bad preset: nothing is baked",
        INPUT,
        &["second-table-invalid.json", "tables[1]"],
        |work, out| {
            let mut v = good_bake(work, out);
            v.push(fixture_dir().join("second-table-invalid.json").into());
            v
        },
    ),
    (
        "preset file too large",
        INPUT,
        &["big.json", "at most 1048576 bytes"],
        |work, out| {
            let mut text = two_tables(4, SECOND_OK);
            text.push_str(&" ".repeat(1 << 20));
            write_preset(work, "big.json", &text);
            let mut v = os(&["bake", "big.json", "--out"]);
            v.push(out.into());
            v
        },
    ),
    (
        "empty presets/ directory",
        INPUT,
        &["presets", "no *.json presets"],
        |work, out| {
            fs::create_dir(work.join("presets")).unwrap();
            let mut v = os(&["bake", "--out"]);
            v.push(out.into());
            v
        },
    ),
    (
        "bad preset in presets/",
        INPUT,
        &["presets/zz-bad.json", "tables[0].kind"],
        |work, out| {
            fs::create_dir(work.join("presets")).unwrap();
            write_preset(
                &work.join("presets"),
                "a-good.json",
                &two_tables(4, SECOND_OK),
            );
            fs::copy(
                fixture_dir().join("unknown-kind.json"),
                work.join("presets/zz-bad.json"),
            )
            .unwrap();
            let mut v = os(&["bake", "--out"]);
            v.push(out.into());
            v
        },
    ),
    (
        "list with a bad preset in presets/",
        INPUT,
        &["presets/bad.json", "tables[0].model.ndf"],
        |work, _| {
            fs::create_dir(work.join("presets")).unwrap();
            fs::copy(
                fixture_dir().join("unknown-ndf.json"),
                work.join("presets/bad.json"),
            )
            .unwrap();
            os(&["list"])
        },
    ),
    (
        "--threads 0",
        INPUT,
        &["--threads", "0 is not in 1..=1024"],
        |work, out| {
            good_bake(work, out)
                .into_iter()
                .chain(os(&["--threads", "0"]))
                .collect()
        },
    ),
    (
        "--threads 1025",
        INPUT,
        &["--threads", "1..=1024"],
        |work, out| {
            good_bake(work, out)
                .into_iter()
                .chain(os(&["--threads", "1025"]))
                .collect()
        },
    ),
    (
        "--threads -1",
        INPUT,
        &["unexpected argument '-1'"],
        |work, out| {
            good_bake(work, out)
                .into_iter()
                .chain(os(&["--threads", "-1"]))
                .collect()
        },
    ),
    (
        "--threads abc",
        INPUT,
        &["--threads", "abc"],
        |work, out| {
            good_bake(work, out)
                .into_iter()
                .chain(os(&["--threads", "abc"]))
                .collect()
        },
    ),
    ("--out without a value", INPUT, &["--out"], |work, _| {
        write_preset(work, "good.json", &two_tables(4, SECOND_OK));
        os(&["bake", "good.json", "--out"])
    }),
    (
        "unknown subcommand",
        INPUT,
        &["unrecognized subcommand", "frobnicate"],
        |_, _| os(&["frobnicate"]),
    ),
    (
        "unknown flag",
        INPUT,
        &["unexpected argument", "--fast"],
        |work, out| {
            good_bake(work, out)
                .into_iter()
                .chain(os(&["--fast"]))
                .collect()
        },
    ),
    (
        "unknown flag of list",
        INPUT,
        &["unexpected argument", "--all"],
        |_, _| os(&["list", "--all"]),
    ),
    // The output directory cannot be created: an environment failure (exit 1), named.
    (
        "output path under a regular file",
        ENV,
        &["cannot create output directory", "afile"],
        |work, _| {
            fs::write(work.join("afile"), b"keep").unwrap();
            let mut v = good_bake(work, &work.join("out"));
            v.pop();
            v.push(work.join("afile").join("sub").into());
            v
        },
    ),
    (
        "output path is a regular file",
        ENV,
        &["cannot create output directory", "afile"],
        |work, _| {
            fs::write(work.join("afile"), b"keep").unwrap();
            let mut v = good_bake(work, &work.join("out"));
            v.pop();
            v.push(work.join("afile").into());
            v
        },
    ),
];

#[test]
fn bad_arguments() {
    for &(name, code, expect, args) in ARG_CASES {
        check_case(name, code, expect, &args);
    }
}

/// The environment-failure cases leave the regular file in the way untouched.
#[test]
fn output_under_a_regular_file_leaves_it_alone() {
    let work = tempfile::tempdir().unwrap();
    fs::write(work.path().join("afile"), b"keep").unwrap();
    write_preset(work.path(), "good.json", &two_tables(4, SECOND_OK));
    let o = run(work.path(), ["bake", "good.json", "--out", "afile/sub"]);
    assert_fails(
        &o,
        ENV,
        &["afile/sub/good", "Not a directory"],
        "--out afile/sub",
    );
    assert_eq!(fs::read(work.path().join("afile")).unwrap(), b"keep");
    let names: Vec<PathBuf> = snapshot(work.path()).into_keys().collect();
    assert_eq!(names, [PathBuf::from("afile"), PathBuf::from("good.json")]);
}

/// No arguments: clap prints the help to stderr and exits 2 (it is not an `error:`).
#[test]
fn no_arguments_prints_help_and_exits_2() {
    let work = tempfile::tempdir().unwrap();
    let o = run(work.path(), std::iter::empty::<&str>());
    assert_eq!(o.status.code(), Some(INPUT), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("Usage: brdfbake <COMMAND>"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("Exit codes:"), "{}", stderr(&o));
    let o = run(work.path(), ["--help"]);
    assert_ok(&o, "--help");
    assert!(stdout(&o).contains("bake"), "{}", stdout(&o));
    let o = run(work.path(), ["--version"]);
    assert_ok(&o, "--version");
    assert!(stdout(&o).starts_with("brdfbake "), "{}", stdout(&o));
}

/// A preset's name is its file stem and becomes a directory under `--out`; a file named
/// `...json` (stem `..`) must not make the bake write outside `--out`.
#[test]

fn preset_file_stem_cannot_escape_the_output_directory() {
    let work = tempfile::tempdir().unwrap();
    write_preset(work.path(), "...json", &two_tables(4, SECOND_OK));
    let out = work.path().join("deep").join("out");
    fs::create_dir_all(&out).unwrap();
    let o = run(
        work.path(),
        ["bake", "./...json", "--out", "deep/out", "-q"],
    );
    let written: Vec<PathBuf> = snapshot(&work.path().join("deep"))
        .into_keys()
        .filter(|p| !p.starts_with("out"))
        .collect();
    assert!(
        written.is_empty(),
        "files written outside --out: {written:?} (exit {:?}, stderr {})",
        o.status.code(),
        stderr(&o)
    );
    assert_fails(&o, INPUT, &["...json"], "bake ./...json");
}

// ---------------------------------------------------------------------------------------
// 5. Atomicity
// ---------------------------------------------------------------------------------------

/// A table that validates but cannot be written: Beckmann D at α = 1e-3 peaks at
/// 1/(πα²) ≈ 3.2e5, beyond f16's 65504, so the error comes after the first table has baked
/// (from the encoder, which refuses a silent inf).
const SECOND_FAILS_AT_BAKE: &str = r#"{"name": "b", "kind": "ndf", "storage": "f16",
    "model": {"ndf": "beckmann"},
    "axes": {"cos_theta_h": {"size": 2, "range": [0.5, 1], "convention": "endpoints"}, "roughness": {"size": 1, "quantity": "alpha", "range": [1e-3, 1e-3]}}}"#;

/// A table that fails validation (α = 0 at the first texel).
const SECOND_INVALID: &str = r#"{"name": "b", "kind": "ndf", "model": {"ndf": "beckmann"},
    "axes": {"cos_theta_h": {"size": 4}, "roughness": {"size": 4, "quantity": "alpha", "convention": "endpoints"}}}"#;

#[test]
fn failed_bake_leaves_previous_outputs_unchanged() {
    let work = tempfile::tempdir().unwrap();
    let w = work.path();
    let out = w.join("out");
    write_preset(w, "p.json", &two_tables(4, SECOND_OK));
    assert_ok(
        &run(w, ["bake", "p.json", "--out", "out", "-q"]),
        "first bake",
    );
    let before = snapshot(&out);
    assert_eq!(before.len(), 4, "{:?}", before.keys());

    let check = |what: &str, o: &Output, code: i32, expect: &[&str]| {
        assert_fails(o, code, expect, what);
        assert_no_temp_files(w, what);
        let after = snapshot(&out);
        assert_eq!(
            after.keys().collect::<Vec<_>>(),
            before.keys().collect::<Vec<_>>(),
            "{what}: the set of output files changed"
        );
        for (p, b) in &before {
            assert!(&after[p] == b, "{what}: {} changed", p.display());
        }
    };

    // The same preset, its first table changed (so a write would show) and its second
    // table invalid: rejected before anything is baked.
    write_preset(w, "p.json", &two_tables(5, SECOND_INVALID));
    let o = run(w, ["bake", "p.json", "--out", "out"]);
    check(
        "second table invalid",
        &o,
        INPUT,
        &["p.json", "tables[1]", "alpha = 0"],
    );

    // The second table fails while baking, after the first has baked.
    write_preset(w, "p.json", &two_tables(5, SECOND_FAILS_AT_BAKE));
    let o = run(w, ["bake", "p.json", "--out", "out"]);
    check(
        "second table fails at bake time",
        &o,
        INPUT,
        &["preset p", "`b`", "f16", "scale"],
    );
    assert!(stdout(&o).is_empty(), "reported a table: {}", stdout(&o));

    // An I/O failure (running as root, a read-only directory would not stop us, so the
    // preset's directory is blocked by a regular file): exit 1, nothing else changes.
    write_preset(w, "q.json", &two_tables(5, SECOND_OK));
    fs::write(out.join("q"), b"in the way").unwrap();
    let before_q = snapshot(&out);
    let o = run(w, ["bake", "q.json", "--out", "out"]);
    assert_fails(
        &o,
        ENV,
        &["cannot create output directory", "q"],
        "blocked q/",
    );
    assert_no_temp_files(w, "blocked q/");
    assert_eq!(snapshot(&out), before_q, "blocked q/: outputs changed");
    fs::remove_file(out.join("q")).unwrap();

    // An output path under a regular file: exit 1, the previous outputs are untouched.
    write_preset(w, "p.json", &two_tables(5, SECOND_OK));
    fs::write(w.join("afile"), b"keep").unwrap();
    let o = run(w, ["bake", "p.json", "--out", "afile/out"]);
    check(
        "output under a regular file",
        &o,
        ENV,
        &["cannot create output directory"],
    );

    // Finally the good bake replaces the outputs in place, leaving no temporary files.
    assert_ok(
        &run(w, ["bake", "p.json", "--out", "out", "-q"]),
        "good bake",
    );
    assert_no_temp_files(w, "good bake");
    let after = snapshot(&out);
    assert_eq!(
        after.keys().collect::<Vec<_>>(),
        before.keys().collect::<Vec<_>>()
    );
    assert_ne!(after[Path::new("p/a.exr")], before[Path::new("p/a.exr")]);
    assert_eq!(after[Path::new("p/b.exr")], before[Path::new("p/b.exr")]);
}

/// If one of a preset's files cannot be replaced (here a directory is in the way of the
/// last one), the bake must fail without replacing the others.
#[test]

fn failed_rename_replaces_no_file() {
    let work = tempfile::tempdir().unwrap();
    let w = work.path();
    let out = w.join("out");
    write_preset(w, "p.json", &two_tables(4, SECOND_OK));
    assert_ok(
        &run(w, ["bake", "p.json", "--out", "out", "-q"]),
        "first bake",
    );
    fs::remove_file(out.join("p/b.json")).unwrap();
    fs::create_dir(out.join("p/b.json")).unwrap();
    fs::write(out.join("p/b.json/keep"), b"x").unwrap();
    let before = snapshot(&out);

    write_preset(w, "p.json", &two_tables(5, SECOND_OK));
    let o = run(w, ["bake", "p.json", "--out", "out"]);
    assert_fails(&o, ENV, &["b.json"], "blocked b.json");
    assert_no_temp_files(w, "blocked b.json");
    let after = snapshot(&out);
    for (p, b) in &before {
        assert!(
            &after[p] == b,
            "{} was replaced by a failed bake",
            p.display()
        );
    }
}

/// `bake p q`: if q fails to write, p must not have been written either ("a failed bake
/// writes nothing"). Today each preset is atomic on its own, so p's files are replaced.
#[test]

fn failed_multi_preset_bake_writes_nothing() {
    let work = tempfile::tempdir().unwrap();
    let w = work.path();
    let out = w.join("out");
    fs::create_dir(&out).unwrap();
    write_preset(w, "p.json", &two_tables(4, SECOND_OK));
    write_preset(w, "q.json", &two_tables(5, SECOND_OK));
    fs::write(out.join("q"), b"in the way").unwrap();
    let o = run(w, ["bake", "p.json", "q.json", "--out", "out", "-q"]);
    assert_fails(&o, ENV, &["cannot create output directory"], "bake p q");
    let written: Vec<PathBuf> = snapshot(&out)
        .into_keys()
        .filter(|p| p != Path::new("q"))
        .collect();
    assert!(written.is_empty(), "a failed bake wrote {written:?}");
}
