//! The Python package (python/, docs/python.md) under pytest: builds the wheel with maturin,
//! installs it into a fresh venv under target/python-test/ and runs python/tests against the
//! brdfbake binary cargo built for this test (the package's arrays, files and messages must be
//! the CLI's). Needs maturin, pytest, numpy and OpenEXR in the judges' venv, which
//! `scripts/test` provisions (scripts/test-requirements.txt) and then requires
//! (tests/common/judges.rs). Offline: the wheel's Rust dependencies come from cargo's cache
//! like the rest of the build, and the fresh venv sees the judges' numpy and pytest through a
//! `.pth` file instead of downloading them.

use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "common/judges.rs"]
mod judges;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn run(what: &str, cmd: &mut Command) -> String {
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot start: {e}"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.status.success(),
        "{what} failed ({}):\n{text}",
        out.status
    );
    text
}

#[test]
fn pytest_suite_passes_against_the_installed_wheel() {
    if !judges::python_wheel() {
        return;
    }
    // the judges' python (the first python3 on the PATH, as scripts/test sets it)
    let python = PathBuf::from("python3");
    let work = Path::new(ROOT).join("target/python-test");
    let wheels = work.join("wheels");
    let _ = std::fs::remove_dir_all(&wheels);
    // the wheel, as a user builds it (docs/python.md), in the shared target dir: the library
    // is already built (cargo releases its lock before running the tests)
    run(
        "maturin build",
        Command::new(&python)
            .current_dir(ROOT)
            .args(["-m", "maturin", "build", "--release", "--offline"])
            .args(["-m", "python/Cargo.toml", "--out"])
            .arg(&wheels),
    );
    let wheel = std::fs::read_dir(&wheels)
        .expect("maturin wrote no wheel folder")
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|x| x == "whl"))
        .expect("maturin wrote no wheel");
    assert!(
        wheel.to_string_lossy().contains("abi3"),
        "not an abi3 wheel: {}",
        wheel.display()
    );

    // a fresh venv each run, seeing the judges' packages (numpy, pytest, OpenEXR) by a .pth
    let venv = work.join("venv");
    let _ = std::fs::remove_dir_all(&venv);
    run(
        "python3 -m venv",
        Command::new(&python).args(["-m", "venv"]).arg(&venv),
    );
    let vpy = venv.join("bin/python");
    let site = |py: &Path| {
        run(
            "sysconfig",
            Command::new(py).args([
                "-c",
                "import sysconfig; print(sysconfig.get_paths()['purelib'])",
            ]),
        )
        .trim()
        .to_string()
    };
    let judges_site = site(&python);
    std::fs::write(
        Path::new(&site(&vpy)).join("judges.pth"),
        format!("{judges_site}\n"),
    )
    .unwrap();
    run(
        "pip install the wheel",
        Command::new(&vpy)
            .args(["-m", "pip", "install", "--quiet", "--no-deps", "--no-index"])
            .args(["--disable-pip-version-check"])
            .arg(&wheel),
    );

    let out = run(
        "pytest python/tests",
        Command::new(&vpy)
            .current_dir(ROOT)
            .args([
                "-m",
                "pytest",
                "-q",
                "-p",
                "no:cacheprovider",
                "python/tests",
            ])
            .env("BRDFBAKE_BIN", env!("CARGO_BIN_EXE_brdfbake"))
            .env_remove("PYTHONPATH"),
    );
    eprintln!("{out}");
}
