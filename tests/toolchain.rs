//! The stated toolchain is true: Cargo.toml's `rust-version` (which the README repeats) is
//! at least the newest `rust-version` any locked dependency declares for this platform, so
//! a user with that toolchain can build the locked tree.

use std::process::Command;

/// `1.88` as [1, 88, 0]: major, minor, patch (a missing part is 0).
fn version(s: &str) -> Vec<u64> {
    let mut v: Vec<u64> = s.split('.').map(|p| p.parse().unwrap_or(0)).collect();
    v.resize(3, 0);
    v
}

#[test]
fn rust_version_covers_every_locked_dependency() {
    let root = env!("CARGO_MANIFEST_DIR");
    let host = {
        let out = Command::new("rustc")
            .arg("-vV")
            .output()
            .expect("rustc -vV");
        let text = String::from_utf8(out.stdout).unwrap();
        text.lines()
            .find_map(|l| l.strip_prefix("host: "))
            .expect("rustc -vV names the host")
            .to_string()
    };
    let out = Command::new(env!("CARGO"))
        .args(["metadata", "--format-version", "1", "--locked", "--offline"])
        .args(["--filter-platform", &host])
        .current_dir(root)
        .output()
        .expect("cargo metadata");
    assert!(
        out.status.success(),
        "cargo metadata: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let used: std::collections::HashSet<&str> = doc["resolve"]["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n["id"].as_str().unwrap())
        .collect();
    let members: Vec<&str> = doc["workspace_members"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    let mut stated: Option<Vec<u64>> = None;
    let mut newest = (vec![0], String::new());
    for p in doc["packages"].as_array().unwrap() {
        let id = p["id"].as_str().unwrap();
        let rv = p["rust_version"].as_str().map(version);
        if members.contains(&id) {
            let rv = rv.unwrap_or_else(|| panic!("{} states no rust-version", p["name"]));
            // (every member states the same one)
            if let Some(s) = &stated {
                assert_eq!(s, &rv, "{} states another rust-version", p["name"]);
            }
            stated = Some(rv);
        } else if used.contains(id) {
            if let Some(rv) = rv {
                if rv > newest.0 {
                    newest = (rv, format!("{} {}", p["name"], p["version"]));
                }
            }
        }
    }
    let stated = stated.expect("a workspace member");
    assert!(
        stated >= newest.0,
        "Cargo.toml states rust-version {stated:?}, but the locked {} needs {:?}",
        newest.1,
        newest.0
    );
    let shown = format!("{}.{}", stated[0], stated[1]);
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    assert!(
        readme.contains(&format!("Rust toolchain ({shown}+)")),
        "the README should state the toolchain Cargo.toml does: Rust {shown}+"
    );
}
