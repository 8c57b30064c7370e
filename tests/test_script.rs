//! The README's test command, `scripts/test`, on a machine without root and without network:
//! run on a copy of the script and the test sources in a temporary directory, with stand-ins
//! on the PATH for what such a machine lacks or must not touch — `chromium`,
//! `glslangValidator`, `spirv-val` and `npm` that fail, `apt-get` and `sudo` that only record
//! being called, a `cmake` 3.x that only prints its version — and pip told to use no index
//! (PyPI unreachable). The real `python3` builds the venv and reads the test sources.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};

/// A temporary repository holding `scripts/test`, its requirements and `tests/*.rs`, and a
/// directory of stand-ins.
fn sandbox() -> tempfile::TempDir {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    fs::create_dir_all(d.join("repo/scripts")).unwrap();
    fs::create_dir_all(d.join("repo/tests")).unwrap();
    for f in ["scripts/test", "scripts/test-requirements.txt"] {
        fs::copy(root.join(f), d.join("repo").join(f)).unwrap();
    }
    for e in fs::read_dir(root.join("tests")).unwrap() {
        let p = e.unwrap().path();
        if p.extension().is_some_and(|x| x == "rs") {
            fs::copy(&p, d.join("repo/tests").join(p.file_name().unwrap())).unwrap();
        }
    }
    let bin = d.join("bin");
    fs::create_dir(&bin).unwrap();
    let calls = d.join("calls");
    let stub = |name: &str, body: &str| {
        use std::os::unix::fs::PermissionsExt;
        let p = bin.join(name);
        fs::write(&p, format!("#!/bin/sh\n{body}\n")).unwrap();
        fs::set_permissions(&p, fs::Permissions::from_mode(0o755)).unwrap();
    };
    for missing in ["chromium", "glslangValidator", "spirv-val", "npm"] {
        stub(missing, "exit 1");
    }
    for recorded in ["apt-get", "sudo"] {
        stub(
            recorded,
            &format!("echo {recorded} \"$@\" >> '{}'; exit 1", calls.display()),
        );
    }
    stub("cmake", "echo 'cmake version 3.31.10'");
    dir
}

fn run(dir: &Path, args: &[&str]) -> Output {
    // the caller's PATH without a venv: scripts/test (and CI) put the real judges' venv on
    // it, whose python3 would find OpenEXR where this machine must not
    let inherited = std::env::var("PATH").unwrap_or_default();
    let inherited: Vec<&str> = inherited
        .split(':')
        .filter(|p| !Path::new(p).join("activate").exists())
        .collect();
    let path = format!("{}:{}", dir.join("bin").display(), inherited.join(":"));
    Command::new("bash")
        .arg(dir.join("repo/scripts/test"))
        .args(args)
        .env("PATH", path)
        .env("PIP_NO_INDEX", "1")
        .env_remove("VIRTUAL_ENV")
        .env_remove("BRDFBAKE_JUDGES")
        .output()
        .expect("bash runs")
}

/// `scripts/test --no-system-judges --setup-only` with every judge missing: it installs
/// nothing system-wide (no apt-get, no sudo), goes on when PyPI and npm fail, lists each
/// judge as missing and names the tests that will skip their checks — every test of the
/// sources that calls a judge (`judges::…`), directly or through a helper — and exits 0
/// with the PATH line for the judges.
#[test]
fn no_system_judges_lists_what_skips_and_installs_nothing() {
    let dir = sandbox();
    let d = dir.path();
    let o = run(d, &["--no-system-judges", "--setup-only"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(!d.join("calls").exists(), "apt-get or sudo was called");
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("export PATH="));
    for j in ["openexr", "chromium", "glslang", "spirv_val", "three_js"] {
        assert!(
            err.lines().any(|l| l.split_whitespace().eq([j, "MISSING"])),
            "{j} not listed as missing:\n{err}"
        );
    }
    assert!(err.contains("pip could not install"), "{err}");
    assert!(err.contains("skip their checks"), "{err}");
    // every test file with a judge appears, with its tests
    let listed: Vec<&str> = err
        .lines()
        .filter_map(|l| l.trim().strip_prefix("tests/"))
        .collect();
    for e in fs::read_dir(d.join("repo/tests")).unwrap() {
        let p = e.unwrap().path();
        let src = fs::read_to_string(&p).unwrap();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        // a call of a judge function (path, name, opening parenthesis)
        let calls = src.split("judges::").skip(1).any(|rest| {
            let id = rest
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(rest.len());
            id > 0 && rest[id..].starts_with('(')
        });
        assert_eq!(
            calls,
            listed.iter().any(|l| l.starts_with(&format!("{name}::"))),
            "{name}:\n{err}"
        );
    }
    for t in [
        "cli_tools.rs::report_is_self_contained_and_renders",
        "exr_openexr.rs::one_d",
        "shader_compilers.rs::ltc_area_light_snippets_compile",
        "gpu_path.rs::default_tables_sample_as_probe_says_on_a_software_gpu",
    ] {
        assert!(listed.contains(&t), "{t}:\n{err}");
    }
}

/// The default (CI) stays strict: the same machine without `--no-system-judges` stops at the
/// first judge it cannot install (exit 1), naming what failed and the way to run without.
#[test]
fn default_mode_stops_at_a_missing_judge() {
    let dir = sandbox();
    let o = run(dir.path(), &["--setup-only"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("pip could not install") && err.contains("scripts/test --no-system-judges"),
        "{err}"
    );
}
