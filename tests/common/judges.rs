//! The independent judges some tests run (OpenEXR's Python bindings, Chromium, ...): found, or
//! what to do when they are missing. Under `scripts/test` (the README's test command, which
//! provisions them) `BRDFBAKE_JUDGES=required` is set and a missing judge fails the test; in a
//! bare `cargo test` the check that needs it is skipped with a notice on stderr.

#![allow(dead_code)]

use std::process::Command;

/// Whether `scripts/test` asked for every judge to be present.
pub fn required() -> bool {
    std::env::var("BRDFBAKE_JUDGES").is_ok_and(|v| v == "required")
}

/// True when `probe` (a command line) runs successfully. Otherwise: panics naming `what` and
/// `how` (how to get it) when judges are required, else prints a skip notice and returns
/// false.
pub fn available(what: &str, probe: &[&str], how: &str) -> bool {
    let ok = Command::new(probe[0])
        .args(&probe[1..])
        .output()
        .is_ok_and(|o| o.status.success());
    if ok {
        return true;
    }
    assert!(
        !required(),
        "{what} is required for this test and is missing: {how} (scripts/test provisions it)"
    );
    eprintln!("{what} not found: this check is skipped ({how}; scripts/test provisions it)");
    false
}

/// Debian's chromium, headless.
pub fn chromium() -> bool {
    available(
        "chromium",
        &["chromium", "--version"],
        "apt-get install chromium",
    )
}

/// python3 with the official OpenEXR bindings and numpy.
pub fn openexr() -> bool {
    available(
        "the OpenEXR Python bindings",
        &["python3", "-c", "import OpenEXR, numpy"],
        "python3 -m pip install openexr numpy",
    )
}

/// python3 with maturin and pytest (the Python package's build and tests: tests/python.rs),
/// numpy and OpenEXR (which the pytest suite reads the CLI's EXR files with).
pub fn python_wheel() -> bool {
    available(
        "maturin and pytest",
        &["python3", "-c", "import maturin, pytest, numpy, OpenEXR"],
        "python3 -m pip install -r scripts/test-requirements.txt",
    )
}

/// Khronos' glslang reference compiler (GLSL ES, desktop and Vulkan GLSL, and HLSL).
pub fn glslang() -> bool {
    available(
        "glslangValidator",
        &["glslangValidator", "--version"],
        "apt-get install glslang-tools",
    )
}

/// The SPIR-V validator of SPIRV-Tools.
pub fn spirv_val() -> bool {
    available(
        "spirv-val",
        &["spirv-val", "--version"],
        "apt-get install spirv-tools",
    )
}

/// three.js, installed by scripts/test with npm under target/test-tools/node (for its
/// KTX2Loader and the ktx-parse module it ships): the package's directory.
pub fn three_js() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target/test-tools/node/node_modules/three");
    let package = dir.join("package.json");
    let probe = package.to_string_lossy().into_owned();
    available(
        "three.js (npm package three)",
        &["test", "-f", &probe],
        "npm install --prefix target/test-tools/node three",
    )
    .then_some(dir)
}
