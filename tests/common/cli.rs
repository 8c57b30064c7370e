//! Running the brdfbake binary in tests: a command, its output, the checks every failing
//! case makes (exit code, `error:` first, the expected fragments, no panic), and a snapshot
//! of a directory to show that a failure wrote nothing.

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Exit code for bad input.
pub const INPUT: i32 = 2;
/// Exit code for a failure (environment, check, tolerance, time limit).
pub const ENV: i32 = 1;

/// The binary, with the test environment's thread setting removed.
pub fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_brdfbake"));
    c.env_remove("RAYON_NUM_THREADS");
    c
}

/// Runs the binary in `cwd`.
pub fn run<S: AsRef<std::ffi::OsStr>>(cwd: &Path, args: &[S]) -> Output {
    bin().args(args).current_dir(cwd).output().unwrap()
}

/// Runs the binary in `cwd`; kills it and fails the test if it is still running after
/// `limit` (a guard against hangs, not a speed test: limits are 10× the expected time or
/// more).
pub fn run_within<S: AsRef<std::ffi::OsStr>>(cwd: &Path, args: &[S], limit: Duration) -> Output {
    let mut child = bin()
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let o = child.wait_with_output().unwrap();
            panic!(
                "brdfbake {:?} still ran after {limit:?} (killed)\nstderr:\n{}",
                args.iter()
                    .map(|a| a.as_ref().to_string_lossy().into_owned())
                    .collect::<Vec<_>>(),
                String::from_utf8_lossy(&o.stderr)
            );
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit `code`, an `error:` message holding every fragment of `expect`, no panic.
pub fn assert_fails(o: &Output, code: i32, expect: &[&str], what: &str) {
    let err = stderr(o);
    assert_eq!(
        o.status.code(),
        Some(code),
        "{what}: wrong exit code\nstdout:\n{}\nstderr:\n{err}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert!(err.starts_with("error:"), "{what}: stderr: {err}");
    assert!(!err.contains("panicked"), "{what}: panicked: {err}");
    for s in expect {
        assert!(err.contains(s), "{what}: stderr lacks {s:?}:\n{err}");
    }
}

/// Every file under `dir` (relative path → bytes); symlinks and other non-files as empty.
pub fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        let Ok(rd) = fs::read_dir(dir) else { return };
        for e in rd {
            let p = e.unwrap().path();
            let t = fs::symlink_metadata(&p).unwrap().file_type();
            if t.is_dir() {
                walk(root, &p, out);
            } else {
                let bytes = if t.is_file() {
                    fs::read(&p).unwrap()
                } else {
                    Vec::new()
                };
                out.insert(p.strip_prefix(root).unwrap().to_path_buf(), bytes);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}
