//! "A failed bake changes nothing", under a kill: a bake of three presets over an older bake
//! of them is stopped before each of its commits (`BRDFBAKE_TEST_PAUSE_BEFORE_COMMIT=k`,
//! a hook in `brdfbake::write` that waits there) by SIGKILL, SIGTERM or SIGINT. Every table
//! then reads as entirely old or entirely new: each of its files byte for byte the old
//! bake's or the new bake's, never a mix, and `inspect` accepts it; the presets committed
//! before the stop are new, the others old. SIGTERM and SIGINT end the process by that
//! signal after removing what it staged; a SIGKILL's staging directories (which no reader
//! opens) are removed by the next bake.

use std::collections::BTreeMap;
use std::fs;
use std::io::{BufRead, BufReader};
use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

#[path = "common/cli.rs"]
mod cli;

const PRESETS: [&str; 3] = ["p0", "p1", "p2"];

/// A preset of two small tables; `size` makes the old and the new bake differ in every file.
fn preset(size: usize) -> String {
    format!(
        r#"{{"schema": "brdfbake.preset/1", "tables": [
          {{"name": "e", "kind": "albedo", "formats": ["exr", "ktx2"],
            "model": {{"ndf": "ggx", "masking": "smith-height-correlated"}},
            "axes": {{"cos_theta_v": {{"size": {size}}}, "roughness": {{"size": {size}, "quantity": "perceptual"}}}}}},
          {{"name": "d", "kind": "ndf", "formats": ["exr", "ktx2"], "model": {{"ndf": "ggx"}},
            "axes": {{"cos_theta_h": {{"size": {size}}}, "roughness": {{"size": 4, "range": [0.3, 1], "quantity": "perceptual"}}}}}}
        ]}}"#
    )
}

/// Every file under `dir/<preset>/`, by relative path.
fn files(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut m = BTreeMap::new();
    for p in PRESETS {
        for e in fs::read_dir(dir.join(p)).unwrap() {
            let e = e.unwrap();
            m.insert(
                format!("{p}/{}", e.file_name().to_string_lossy()),
                fs::read(e.path()).unwrap(),
            );
        }
    }
    m
}

/// Bakes the presets of `src` (a folder with p0.json ... p2.json) into `out`.
fn bake(d: &Path, src: &str, out: &str) {
    let mut args = vec!["bake".to_string()];
    args.extend(PRESETS.map(|p| format!("{src}/{p}.json")));
    args.extend(["--out".into(), out.into(), "-q".into()]);
    let o = cli::run(d, &args);
    assert!(o.status.success(), "{}", cli::stderr(&o));
}

#[test]
fn every_table_is_entirely_old_or_entirely_new_after_a_kill_at_any_commit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (src, size) in [("old", 8), ("new", 9)] {
        fs::create_dir(d.join(src)).unwrap();
        for p in PRESETS {
            fs::write(d.join(src).join(format!("{p}.json")), preset(size)).unwrap();
        }
    }
    bake(d, "old", "ref-old");
    bake(d, "new", "ref-new");
    let (old, new) = (files(&d.join("ref-old")), files(&d.join("ref-new")));
    assert_eq!(old.len(), PRESETS.len() * 6);
    assert!(old.iter().all(|(k, v)| new.get(k).is_some_and(|n| n != v)));

    let mut case = 0;
    for k in 0..PRESETS.len() {
        for (signal, name) in [
            (libc::SIGKILL, "SIGKILL"),
            (libc::SIGTERM, "SIGTERM"),
            (libc::SIGINT, "SIGINT"),
        ] {
            case += 1;
            let out = format!("out{case}");
            bake(d, "old", &out);
            let mut child = cli::bin()
                .arg("bake")
                .args(PRESETS.map(|p| format!("new/{p}.json")))
                .args(["--out", &out, "-q"])
                .env("BRDFBAKE_TEST_PAUSE_BEFORE_COMMIT", k.to_string())
                .current_dir(d)
                .stdin(Stdio::null())
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap();
            let mut err = BufReader::new(child.stderr.take().unwrap());
            let mut line = String::new();
            let start = Instant::now();
            while !line.contains("paused before commit") {
                line.clear();
                assert!(
                    err.read_line(&mut line).unwrap() > 0,
                    "the bake ended without pausing"
                );
                assert!(start.elapsed() < Duration::from_secs(120));
            }
            assert!(
                line.contains(&format!("commit {k} of {}", PRESETS.len())),
                "{line}"
            );
            // SAFETY: signalling our own child
            assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, signal) }, 0);
            let status = child.wait().unwrap();
            assert_eq!(
                status.signal(),
                Some(signal),
                "{name} at commit {k}: {status:?}"
            );

            let what = format!("{name} before commit {k}");
            let now = files(&d.join(&out));
            assert_eq!(now.len(), old.len(), "{what}: files {:?}", now.keys());
            for (path, bytes) in &now {
                let committed = PRESETS.iter().position(|p| path.starts_with(p)).unwrap() < k;
                let want = if committed { &new[path] } else { &old[path] };
                assert!(
                    bytes == want,
                    "{what}: {path} is neither as committed nor as before"
                );
            }
            for p in PRESETS {
                for t in ["e", "d"] {
                    let o = cli::run(d, &["inspect", &format!("{out}/{p}/{t}.ktx2")]);
                    assert!(o.status.success(), "{what}: {p}/{t}: {}", cli::stderr(&o));
                }
            }
            // what was staged: removed on SIGTERM/SIGINT; after SIGKILL, by the next bake
            let hidden = |out: &str| -> Vec<String> {
                fs::read_dir(d.join(out))
                    .unwrap()
                    .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                    .filter(|n| n.starts_with('.'))
                    .collect()
            };
            if signal != libc::SIGKILL {
                assert!(hidden(&out).is_empty(), "{what}: left {:?}", hidden(&out));
            } else {
                bake(d, "new", &out);
                assert!(
                    hidden(&out).is_empty(),
                    "{what}: the next bake left {:?}",
                    hidden(&out)
                );
                assert!(files(&d.join(&out)) == new, "{what}: the next bake");
            }
        }
    }
}
