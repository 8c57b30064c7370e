//! Integrity end to end (issue 21): every case of the issue, as a user meets it, gives a
//! specific message and the right exit code, and writes nothing:
//!
//! - a table whose error estimate misses its tolerance fails (exit 1) unless the preset
//!   accepts the estimate, which the sidecar then records; no single integral runs away;
//! - stored values that underflow their storage are an error like overflow;
//! - outputs are checkable: every flipped byte, replaced file, edited sidecar and half-old
//!   set is found by `bake --check`, and by `inspect`, `probe` and `verify`;
//! - no input can hang a command or grow its memory without bound (devices, FIFOs, huge
//!   tolerances, huge tables), and every command has the resource guards;
//! - a full stdout is exit 1, never a panic; flags that do not apply are errors.

#[path = "common/cli.rs"]
mod cli_support;

use cli_support::{assert_fails, run, run_within, snapshot, ENV, INPUT};
use serde_json::Value;
use std::fs;
use std::path::Path;
use std::time::Duration;

/// A guard against hangs (not a speed test): every case here finishes in well under a second
/// or two on the 2-core benchmark machine.
const HANG: Duration = Duration::from_secs(120);

fn write(dir: &Path, name: &str, text: &str) {
    fs::write(dir.join(name), text).unwrap();
}

fn table(extra: &str, kind_model_axes: &str) -> String {
    format!(
        r#"{{"schema": "brdfbake.preset/1", "tables": [{{"name": "t", {extra} {kind_model_axes}}}]}}"#
    )
}

/// Runs a failing case in `d` and checks that no file under `d` changed.
fn fails_writing_nothing(d: &Path, args: &[&str], code: i32, expect: &[&str]) {
    let before = snapshot(d);
    let o = run_within(d, args, HANG);
    assert_fails(&o, code, expect, &args.join(" "));
    assert_eq!(snapshot(d), before, "{args:?} changed files");
}

// ---------------------------------------------------------------------------------------
// 2. A bake that misses its tolerance does not succeed silently
// ---------------------------------------------------------------------------------------

/// Ward–Dür's 1/√(cos θi cos θo) at cos θ ∈ [1e-9, 2e-9]: its albedo cannot be integrated
/// to 1e-7. The bake stops at the per-integral budget (it ran 130 s before) and fails
/// naming the texels and the estimate.
#[test]
fn singular_integrand_fails_with_its_texels() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        "ward.json",
        &table(
            "",
            r#""kind": "classic-albedo", "model": {"classic": {"type": "ward-duer", "rho_d": 0, "rho_s": 1}},
               "axes": {"cos_theta_v": {"size": 2, "range": [1e-9, 2e-9]},
                        "roughness": {"size": 2, "quantity": "alpha", "range": [0.1, 0.8]}}"#,
        ),
    );
    fails_writing_nothing(
        d,
        &["bake", "ward.json", "--out", "out"],
        ENV,
        &[
            "table \"t\"",
            "error estimate exceeds its tolerance 1e-7",
            "4 texel channel(s) of 4 texels",
            "E at texel [0, 0] (cos_theta_v=1.25e-9, roughness=0.275)",
            "Nothing was written",
            "accept_error_estimate",
        ],
    );
    assert!(!d.join("out").exists());
}

/// A GGX split sum with V-groove masking at α ∈ [1e-9, 2e-9]: estimates just over the
/// tolerance fail; `accept_error_estimate` accepts them, the sidecar says so, and the input
/// hash differs from the strict table's (a different promise).
#[test]
fn estimate_over_tolerance_fails_unless_accepted() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let body = r#""kind": "dfg", "layout": "filament", "model": {"ndf": "ggx", "masking": "v-groove"},
        "axes": {"cos_theta_v": {"size": 4}, "roughness": {"size": 4, "quantity": "alpha", "range": [1e-9, 2e-9]}}"#;
    write(d, "strict.json", &table("", body));
    fails_writing_nothing(
        d,
        &["bake", "strict.json", "--out", "out"],
        ENV,
        &["error estimate exceeds its tolerance 1e-7", "texel ["],
    );
    write(
        d,
        "loose.json",
        &table(r#""accept_error_estimate": 1e-6,"#, body),
    );
    let o = run_within(d, &["bake", "loose.json", "--out", "out"], HANG);
    assert_eq!(o.status.code(), Some(0), "{}", cli_support::stderr(&o));
    let side: Value =
        serde_json::from_slice(&fs::read(d.join("out/loose/t.json")).unwrap()).unwrap();
    assert_eq!(side["quadrature"]["accept_error_estimate"], 1e-6);
    let est = side["quadrature"]["estimated_max_error"]["R"]
        .as_f64()
        .unwrap()
        .max(
            side["quadrature"]["estimated_max_error"]["G"]
                .as_f64()
                .unwrap(),
        );
    assert!(est > 1e-7 && est <= 1e-6, "{est}");
    // the accepted table reads back (its sidecar rebuilds the same inputs)
    let o = run(d, &["inspect", "out/loose/t.exr", "--json"]);
    let doc: Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(doc["input_hash_consistent"], true, "{doc}");
    // an accepted estimate below the tolerance is refused as meaningless
    write(
        d,
        "bad.json",
        &table(r#""accept_error_estimate": 1e-9,"#, body),
    );
    fails_writing_nothing(
        d,
        &["bake", "bad.json", "--out", "out"],
        INPUT,
        &[
            "tables[0].accept_error_estimate",
            "must be a number in [tolerance, 1]",
        ],
    );
}

/// Stored values that underflow (to zero, or to a few subnormal bits) are an error like
/// overflow, naming the table, a texel and the scale.
#[test]
fn scale_underflow_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let axes = r#""kind": "ndf", "model": {"ndf": "ggx"},
        "axes": {"cos_theta_h": {"size": 8}, "roughness": {"size": 4, "quantity": "alpha"}}"#;
    for (name, extra, storage) in [
        ("tiny", r#""scale": 5e-324,"#, "f32"),
        ("half", r#""scale": 1e-8, "storage": "f16","#, "f16"),
    ] {
        write(d, &format!("{name}.json"), &table(extra, axes));
        fails_writing_nothing(
            d,
            &["bake", &format!("{name}.json"), "--out", "out"],
            INPUT,
            &[
                "table t: scale",
                &format!("underflow {storage}"),
                "texel [",
                "raise \"scale\"",
            ],
        );
    }
}

/// A cosine too close to grazing for the integrand: the same specific message from `eval`
/// and `bake` (it was `E = NaN` with exit 0, and "texel [0, 0, 0] is not finite").
#[test]
fn grazing_cosines_below_the_limit_say_what_to_change() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fails_writing_nothing(
        d,
        &["eval", "e", "--alpha", "0.5", "--cos-theta", "1e-155"],
        INPUT,
        &[
            "cosine 1e-155",
            "below the smallest accepted 1e-12",
            "give a cosine of 1e-12 or above",
        ],
    );
    write(
        d,
        "g.json",
        &table(
            "",
            r#""kind": "albedo", "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
               "axes": {"cos_theta_v": {"size": 2, "range": [1e-155, 1e-150]}, "roughness": {"size": 2, "quantity": "alpha"}}"#,
        ),
    );
    fails_writing_nothing(
        d,
        &["bake", "g.json", "--out", "out"],
        INPUT,
        &[
            "axes.cos_theta_v",
            "below the smallest accepted 1e-12",
            "start the range at 1e-12",
        ],
    );
    // at the limit itself the value is finite and meets its tolerance
    let o = run(d, &["eval", "e", "--alpha", "0.5", "--cos-theta", "1e-12"]);
    assert_eq!(o.status.code(), Some(0), "{}", cli_support::stderr(&o));
}

// ---------------------------------------------------------------------------------------
// 3. Outputs are checkable
// ---------------------------------------------------------------------------------------

const SMALL: &str = r#"{"schema": "brdfbake.preset/1", "tables": [
  {"name": "g1", "kind": "g1", "model": {"ndf": "ggx"}, "formats": ["exr", "ktx2", "png", "h"],
   "axes": {"cos_theta": {"size": 8}, "roughness": {"size": 4, "quantity": "alpha"}}},
  {"name": "e", "kind": "albedo", "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
   "formats": ["exr"],
   "axes": {"cos_theta_v": {"size": 4}, "roughness": {"size": 3, "quantity": "perceptual"}}}
]}"#;

/// A directory with `small.json` baked into `out/`.
fn baked() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), "small.json", SMALL);
    let o = run(dir.path(), &["bake", "small.json", "--out", "out"]);
    assert_eq!(o.status.code(), Some(0), "{}", cli_support::stderr(&o));
    dir
}

fn check(d: &Path) -> std::process::Output {
    run_within(d, &["bake", "small.json", "--out", "out", "--check"], HANG)
}

/// The cases of the issue: a zero-byte EXR, a KTX2 of random bytes, another table's EXR
/// copied over, a GGX texture beside a Beckmann sidecar, and sidecar edits to coordinates,
/// alpha, channel names and dimensions. `bake --check` names each file (exit 1); `inspect`,
/// `probe` and `verify` refuse it naming it (exit 2).
#[test]
fn damaged_replaced_and_edited_outputs_are_named() {
    type Damage = fn(&Path);
    let cases: [(&str, Damage, &str, &str); 8] = [
        (
            "zero-byte exr",
            |d| fs::write(d.join("out/small/g1.exr"), b"").unwrap(),
            "g1.exr",
            "do not match the digest",
        ),
        (
            "random ktx2",
            |d| {
                let mut x: u64 = 0x2545_f491_4f6c_dd1d;
                let bytes: Vec<u8> = (0..600)
                    .map(|_| {
                        x ^= x << 13;
                        x ^= x >> 7;
                        x ^= x << 17;
                        x as u8
                    })
                    .collect();
                fs::write(d.join("out/small/g1.ktx2"), bytes).unwrap()
            },
            "g1.ktx2",
            "do not match the digest",
        ),
        (
            "another table's exr",
            |d| {
                fs::copy(d.join("out/small/e.exr"), d.join("out/small/g1.exr")).unwrap();
            },
            "g1.exr",
            "do not match the digest",
        ),
        (
            "coordinates edited",
            |d| {
                edit(
                    d,
                    "\"coordinates\": [\n        0.0625",
                    "\"coordinates\": [\n        0.0626",
                )
            },
            "g1.json",
            "sidecar_digest",
        ),
        (
            "alpha edited",
            |d| {
                edit(
                    d,
                    "\"alpha\": [\n        0.125",
                    "\"alpha\": [\n        0.25",
                )
            },
            "g1.json",
            "sidecar_digest",
        ),
        (
            "channel renamed",
            |d| edit(d, "\"name\": \"G1\"", "\"name\": \"G2\""),
            "g1.json",
            "sidecar_digest",
        ),
        (
            "dimensions edited",
            |d| edit(d, "\"dimensions\": 2", "\"dimensions\": 3"),
            "g1.json",
            "sidecar_digest",
        ),
        (
            "a flipped byte in a preview",
            |d| flip(&d.join("out/small/g1.preview-G1.png"), 100),
            "g1.preview-G1.png",
            "do not match the digest",
        ),
    ];
    fn edit(d: &Path, from: &str, to: &str) {
        let p = d.join("out/small/g1.json");
        let t = fs::read_to_string(&p).unwrap();
        assert!(t.contains(from), "{from:?} not in the sidecar");
        fs::write(p, t.replacen(from, to, 1)).unwrap();
    }
    for (what, damage, file, why) in cases {
        let dir = baked();
        let d = dir.path();
        damage(d);
        let o = check(d);
        assert_eq!(o.status.code(), Some(ENV), "{what}");
        let out = String::from_utf8_lossy(&o.stdout);
        assert!(
            out.contains(&format!("small/g1: out/small/{file}")) && out.contains(why),
            "{what}: --check said\n{out}"
        );
        if !file.ends_with(".png") {
            for cmd in [
                &["inspect", "out/small/g1.exr"][..],
                &["verify", "out/small/g1.ktx2"],
                &[
                    "probe",
                    "out/small/g1.exr",
                    "--at",
                    "cos_theta=0.5,roughness=0.5",
                ],
            ] {
                let texture = cmd[1];
                // (the texture a damage did not touch is still checked against its sidecar)
                if file.ends_with("ktx2") && texture.ends_with("exr")
                    || file.ends_with("exr") && texture.ends_with("ktx2")
                {
                    continue;
                }
                let o = run_within(d, cmd, HANG);
                assert_fails(&o, INPUT, &[file, why], &format!("{what}: {cmd:?}"));
            }
        }
    }
}

/// A GGX texture beside a Beckmann sidecar (both brdfbake's, sealed): the texture's own
/// header hash is not its sidecar's.
#[test]
fn texture_of_another_table_beside_a_sealed_sidecar() {
    let dir = baked();
    let d = dir.path();
    let beckmann = SMALL.replace(
        "\"ndf\": \"ggx\"}, \"formats\"",
        "\"ndf\": \"beckmann\"}, \"formats\"",
    );
    write(d, "b.json", &beckmann);
    assert_eq!(
        run(d, &["bake", "b.json", "--out", "out"]).status.code(),
        Some(0)
    );
    // the Beckmann sidecar sealed over the GGX texture (as no bake writes it)
    let ggx = fs::read(d.join("out/small/g1.exr")).unwrap();
    let side: Value = serde_json::from_slice(&fs::read(d.join("out/b/g1.json")).unwrap()).unwrap();
    fs::create_dir(d.join("mix")).unwrap();
    fs::write(d.join("mix/g1.exr"), &ggx).unwrap();
    fs::write(
        d.join("mix/g1.json"),
        brdfbake::digest::seal(side, &[("g1.exr", ggx.as_slice())]),
    )
    .unwrap();
    let o = run(d, &["inspect", "mix/g1.exr"]);
    assert_fails(
        &o,
        INPUT,
        &[
            "mix/g1.exr",
            "header's input hash",
            "baked for another table",
        ],
        "mixed pair",
    );
}

/// An interrupted set: one table's new texture beside its old sidecar (a kill between the
/// renames) is found; so is a file left missing.
#[test]
fn half_old_half_new_set_is_found() {
    let dir = baked();
    let d = dir.path();
    let old_side = fs::read(d.join("out/small/g1.json")).unwrap();
    // a new bake of an edited preset, then the old sidecar back in place
    write(
        d,
        "small.json",
        &SMALL.replace("\"size\": 8", "\"size\": 9"),
    );
    assert_eq!(
        run(d, &["bake", "small.json", "--out", "out"])
            .status
            .code(),
        Some(0)
    );
    fs::write(d.join("out/small/g1.json"), &old_side).unwrap();
    let o = check(d);
    assert_eq!(o.status.code(), Some(ENV));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("out/small/g1.json: stale"), "{out}");
    assert!(out.contains("out/small/g1.exr: damaged or stale"), "{out}");
    fs::remove_file(d.join("out/small/e.exr")).unwrap();
    let out = String::from_utf8_lossy(&check(d).stdout).into_owned();
    assert!(out.contains("out/small/e.exr: missing"), "{out}");
}

/// Any single flipped byte in any output is found by `bake --check`: every file of a bake,
/// at byte positions spread over each file (the first and last bytes, and 8 more from a
/// fixed-seed generator), each flipped by a different bit pattern.
#[test]
fn every_single_flipped_byte_is_found_by_check() {
    let dir = baked();
    let d = dir.path();
    assert_eq!(check(d).status.code(), Some(0));
    let files: Vec<_> = fs::read_dir(d.join("out/small"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(files.len() >= 7, "{files:?}");
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        seed >> 33
    };
    for f in &files {
        let good = fs::read(f).unwrap();
        let n = good.len() as u64;
        let mut at: Vec<u64> = vec![0, n - 1];
        at.extend((0..8).map(|_| next() % n));
        for &i in &at {
            let mut bad = good.clone();
            let x = (next() % 255 + 1) as u8; // never 0
            bad[i as usize] ^= x;
            fs::write(f, &bad).unwrap();
            let o = check(d);
            let name = f.file_name().unwrap().to_string_lossy();
            assert_eq!(
                o.status.code(),
                Some(ENV),
                "byte {i} of {name} ^ {x:#x} went unnoticed"
            );
            assert!(String::from_utf8_lossy(&o.stdout).contains(name.as_ref()));
            fs::write(f, &good).unwrap();
        }
    }
    assert_eq!(check(d).status.code(), Some(0));
}

/// Temporary files a killed bake left (their process gone) are swept by the next bake into
/// that directory, whatever their number.
#[test]
fn leftover_temporary_files_are_swept() {
    let dir = baked();
    let d = dir.path();
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let dead = child.id();
    child.wait().unwrap();
    for n in 0..200 {
        fs::write(
            d.join(format!("out/small/.g1.exr.tmp-{dead}-{n}")),
            b"partial",
        )
        .unwrap();
    }
    assert_eq!(
        run(d, &["bake", "small.json", "--out", "out"])
            .status
            .code(),
        Some(0)
    );
    let left: Vec<String> = fs::read_dir(d.join("out/small"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp-"))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// `verify --all` recomputes every texel; the default a spread of them.
#[test]
fn verify_all_recomputes_every_texel() {
    let dir = baked();
    let d = dir.path();
    let n = |args: &[&str]| -> u64 {
        let o = run_within(d, args, HANG);
        let v: Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(v["ok"], true, "{v}");
        v["tables"][0]["texels_checked"].as_u64().unwrap()
    };
    assert_eq!(n(&["verify", "out/small/e.exr", "--all", "--json"]), 12);
    assert_eq!(n(&["verify", "out/small/g1.exr", "--all", "--json"]), 32);
}

// ---------------------------------------------------------------------------------------
// 4. No hangs, no unbounded reads, no panics
// ---------------------------------------------------------------------------------------

/// Devices and FIFOs are refused before they are opened (a FIFO would block the open
/// forever; /dev/zero streams without end), for every command that reads a file.
#[cfg(unix)]
#[test]
fn devices_and_fifos_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let fifo = d.join("fifo.json");
    let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    for path in ["/dev/zero", "fifo.json"] {
        for args in [
            vec!["measured", path],
            vec!["laws", &format!("merl:{path}")],
            vec!["report", "smith-g", "--filament-dfg", path, "--out", "rep"],
            vec!["bake", path, "--out", "out"],
            vec!["verify", path],
        ] {
            let args: Vec<&str> = args.iter().map(|s| s.as_ref()).collect();
            fails_writing_nothing(d, &args, INPUT, &["not a regular file"]);
        }
    }
}

/// Requests whose work is unbounded or huge are refused up front or stopped: tolerances
/// past f64's reach, a preset bake refuses for memory given to verify and report, a shipped
/// table too large for the time limit.
#[test]
fn huge_requests_are_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for tol in ["1e-16", "1e-300", "0.5"] {
        fails_writing_nothing(
            d,
            &["laws", "ggx", "--tolerance", tol],
            INPUT,
            &["--tolerance must be in [1e-12, 0.01]"],
        );
    }
    write(
        d,
        "big.json",
        &table(
            "",
            r#""kind": "g2", "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
               "axes": {"cos_theta_v": {"size": 256}, "cos_theta_l": {"size": 256}, "roughness": {"size": 256, "quantity": "alpha"}}"#,
        ),
    );
    for cmd in ["bake", "verify", "report"] {
        fails_writing_nothing(
            d,
            &[cmd, "big.json", "--max-memory", "64MiB"],
            INPUT,
            &["of memory", "--max-memory"],
        );
    }
    // a 1024² shipped Filament table: ~10⁶ exact values, minutes of work
    let mut inc = String::with_capacity(1024 * 1024 * 2 * 8);
    for _ in 0..1024 * 1024 * 2 {
        inc.push_str("0x3c00, ");
    }
    write(d, "dfg.inc", &inc);
    fails_writing_nothing(
        d,
        &[
            "report",
            "smith-g",
            "--filament-dfg",
            "dfg.inc",
            "--max-time",
            "5",
            "--out",
            "rep",
        ],
        INPUT,
        &["this report needs an estimated", "--max-time"],
    );
}

/// A MERL file of huge values (it took 481 s) is refused as not measured data.
#[test]
fn merl_file_of_huge_values_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let n = 90 * 90 * 180;
    let mut b = Vec::with_capacity(12 + 24 * n);
    for x in [90i32, 90, 180] {
        b.extend_from_slice(&x.to_le_bytes());
    }
    for _ in 0..3 * n {
        b.extend_from_slice(&1e300f64.to_le_bytes());
    }
    fs::write(d.join("huge.binary"), b).unwrap();
    for args in [
        &["measured", "huge.binary"][..],
        &["laws", "merl:huge.binary"],
    ] {
        fails_writing_nothing(
            d,
            args,
            INPUT,
            &["huge.binary", "above 1e6/sr", "not measured BRDF data"],
        );
    }
}

/// Writing into a full stdout is exit 1 with a message (it panicked with exit 101).
#[cfg(target_os = "linux")]
#[test]
fn full_stdout_is_an_error_not_a_panic() {
    let dir = baked();
    let d = dir.path();
    for args in [
        &["list"][..],
        &["bake", "small.json", "--out", "out2"],
        &["bake", "small.json", "--out", "out2", "--json"],
        &["inspect", "out/small/g1.exr", "--json"],
        &["eval", "d", "--alpha", "0.5", "--cos-theta", "0.5"],
        &["report", "small.json", "--out", "rep"],
        &["verify", "out/small/g1.exr"],
        &[
            "probe",
            "out/small/g1.exr",
            "--at",
            "cos_theta=0.5,roughness=0.5",
        ],
        &["laws", "ggx"],
        &["--help"],
    ] {
        let o = cli_support::bin()
            .args(args)
            .current_dir(d)
            .stdout(
                fs::OpenOptions::new()
                    .write(true)
                    .open("/dev/full")
                    .unwrap(),
            )
            .output()
            .unwrap();
        assert_fails(&o, ENV, &["cannot write to stdout"], &format!("{args:?}"));
    }
}

// ---------------------------------------------------------------------------------------
// 5. Messages and flags
// ---------------------------------------------------------------------------------------

#[test]
fn bad_input_names_the_field_or_flag() {
    let dir = baked();
    let d = dir.path();
    let g1 = r#""kind": "g1", "model": {"ndf": "ggx"},
        "axes": {"cos_theta": {"size": 8}, "roughness": {"size": 4, "quantity": "alpha"}}"#;
    write(
        d,
        "dup.json",
        &table(r#""formats": ["exr", "ktx2", "exr"],"#, g1),
    );
    write(
        d,
        "range3.json",
        &table(
            "",
            r#""kind": "g1", "model": {"ndf": "ggx"},
               "axes": {"cos_theta": {"size": 8, "range": [0, 0.5, 1]}, "roughness": {"size": 4, "quantity": "alpha"}}"#,
        ),
    );
    write(d, "hugescale.json", &table(r#""scale": 1e300,"#, g1));
    fs::write(d.join("x.png"), b"\x89PNG\r\n\x1a\n").unwrap();
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["bake", "dup.json"],
            &["tables[0].formats[2]", "\"exr\" is listed twice"],
        ),
        (
            &["bake", "small.json", "--format", "exr,exr"],
            &["--format", "\"exr\" is listed twice"],
        ),
        (
            &["report", "--filament-dfg", "missing.inc"],
            &["--filament-dfg", "missing.inc: no such file"],
        ),
        (
            &["bake", "range3.json"],
            &[
                "tables[0].axes.cos_theta.range",
                "must be two numbers [lo, hi], got 3",
            ],
        ),
        (
            &["bake", "hugescale.json"],
            &["tables[0].scale", "got 1e300"],
        ),
        (
            &["eval", "dfg", "--alpha", "0.5", "--cos-theta", "NaN"],
            &["--cos-theta NaN is not a cosine"],
        ),
        (
            &["verify", "x.png"],
            &["x.png: not a png-data file brdfbake wrote", "preview"],
        ),
        (
            &[
                "eval",
                "sheen",
                "--ndf",
                "ggx",
                "--alpha",
                "0.5",
                "--cos-theta",
                "0.5",
            ],
            &["--ndf does not apply to `eval sheen`"],
        ),
        (
            &["eval", "e-avg", "--alpha", "0.5", "--cos-theta", "0.5"],
            &["--cos-theta does not apply to `eval e-avg`"],
        ),
        (
            &[
                "eval",
                "d",
                "--f0",
                "0.04",
                "--alpha",
                "0.5",
                "--cos-theta",
                "0.5",
            ],
            &["--f0 does not apply to `eval d`"],
        ),
        (
            &[
                "eval",
                "g2",
                "--masking",
                "fancy",
                "--alpha",
                "0.5",
                "--cos-theta",
                "0.5",
                "--cos-theta-l",
                "0.5",
            ],
            &["--masking: unknown value \"fancy\""],
        ),
        (
            &["laws", "ggx:alpha=0.5,alpha=0.3"],
            &["key \"alpha\" is given twice"],
        ),
        (
            &["laws", "ward:alpha=0.1,alpha_x=0.2"],
            &["alpha and alpha_x conflict"],
        ),
    ];
    for (args, expect) in cases {
        fails_writing_nothing(d, args, INPUT, expect);
    }
    let o = run(d, &["bake", "hugescale.json"]);
    assert!(
        !cli_support::stderr(&o).contains("00000000000"),
        "long digits"
    );
}

/// KTX2 files other tools wrote are refused with their writer and format named plainly (no
/// Rust `Some(…)`, no NUL bytes).
#[test]
fn foreign_ktx2_files_are_named_plainly() {
    let dir = baked();
    let d = dir.path();
    let ktx = fs::read(d.join("out/small/g1.ktx2")).unwrap();
    // another writer, same length: "brdfbake 0.1.0" -> "toktx v4.3.2.1"
    let at = ktx.windows(9).position(|w| w == b"brdfbake ").unwrap();
    let mut other = ktx.clone();
    let w = format!("brdfbake {}", env!("CARGO_PKG_VERSION"));
    let t: String = "toktx v4.3.2.1-beta-long-enough"
        .chars()
        .take(w.len())
        .collect();
    other[at..at + w.len()].copy_from_slice(t.as_bytes());
    fs::write(d.join("toktx.ktx2"), &other).unwrap();
    let o = run(d, &["inspect", "toktx.ktx2"]);
    assert_fails(
        &o,
        INPUT,
        &["toktx.ktx2", &format!("KTXwriter is \"{t}\"")],
        "toktx",
    );
    assert!(!cli_support::stderr(&o).contains("\\0"));
    // a block-compressed format (BC7_UNORM_BLOCK = 145) with our writer
    let mut bc7 = ktx;
    bc7[12..16].copy_from_slice(&145u32.to_le_bytes());
    fs::write(d.join("bc7.ktx2"), &bc7).unwrap();
    let o = run(d, &["inspect", "bc7.ktx2"]);
    assert_fails(
        &o,
        INPUT,
        &["bc7.ktx2", "vkFormat is BC7_UNORM_BLOCK"],
        "bc7",
    );
    assert!(!cli_support::stderr(&o).contains("Some("));
}

fn flip(p: &Path, at: usize) {
    let mut b = fs::read(p).unwrap();
    b[at] ^= 0x40;
    fs::write(p, b).unwrap();
}
