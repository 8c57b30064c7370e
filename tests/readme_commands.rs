//! Every command line of the README runs as written: in a fresh directory that holds only
//! what a clone holds (`presets/`, `tests/data/`: links to the repository's), the README's bake
//! first, then each line of its `sh` blocks in order through `sh -e`, with `brdfbake` on the
//! PATH (`cargo run --release --` is that binary). A line fails the test if it exits non-zero.
//! The test command itself (`scripts/test`) is the one line not run here: CI runs it.

use std::process::Command;

/// The lines of the README's ```sh blocks, comments kept (sh ignores them).
fn readme_lines() -> Vec<String> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let mut out = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            inside = !inside && line.trim() == "```sh";
            continue;
        }
        if inside && !line.trim().is_empty() {
            out.push(line.to_string());
        }
    }
    out
}

/// Lines run elsewhere, each with where.
const RUN_ELSEWHERE: &[(&str, &str)] = &[("scripts/test", "CI (.ci/run) runs the test command")];

#[test]
fn every_readme_command_runs_as_written() {
    let repo = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::os::unix::fs::symlink(repo.join("presets"), d.join("presets")).unwrap();
    std::fs::create_dir(d.join("tests")).unwrap();
    std::os::unix::fs::symlink(repo.join("tests/data"), d.join("tests/data")).unwrap();
    let bin = d.join("bin");
    std::fs::create_dir(&bin).unwrap();
    std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_brdfbake"), bin.join("brdfbake")).unwrap();
    let path = format!(
        "{}:{}",
        bin.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let lines = readme_lines();
    assert!(lines.len() >= 10, "the README's sh blocks: {lines:?}");
    let mut ran = 0;
    for line in &lines {
        let cmd = line.replace("cargo run --release --", "brdfbake");
        let cmd = cmd.trim();
        if let Some((_, why)) = RUN_ELSEWHERE.iter().find(|(p, _)| cmd.starts_with(p)) {
            eprintln!("not run here ({why}): {cmd}");
            continue;
        }
        let out = Command::new("sh")
            .args(["-e", "-c", cmd])
            .current_dir(d)
            .env("PATH", &path)
            .env_remove("RAYON_NUM_THREADS")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "README line `{line}` failed ({}):\n{}{}",
            out.status,
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        ran += 1;
    }
    eprintln!("{ran} README lines ran");
    // the README's bake made what its lines use
    assert!(d.join("out/filament-dfg/dfg.exr").exists());
}
