//! The house rule that no two files of the library import each other, directly or through
//! others: `scripts/import-graph.py --check` builds the file-level import graph of src/
//! (after re-exports, so an item counts where it is defined) and fails on any cycle, naming
//! the files and edges. One direction of flow keeps every file readable on its own terms.

use std::process::Command;

#[test]
fn no_import_cycles_between_files() {
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/scripts/import-graph.py");
    let o = Command::new("python3")
        .args([script, "--check"])
        .output()
        .expect("python3 runs scripts/import-graph.py");
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "import cycles:\n{out}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    // the graph is not empty: the script found the files and their edges
    let n: usize = out
        .trim()
        .strip_prefix("no cycles among ")
        .and_then(|s| s.strip_suffix(" files"))
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    assert!(n > 50, "{out}");
    let edges = Command::new("python3")
        .args([script, "--edges"])
        .output()
        .unwrap();
    let edges = String::from_utf8_lossy(&edges.stdout);
    assert!(
        edges.contains("src/table/albedo.rs -> src/table/methods.rs"),
        "the graph lost a known edge:\n{edges}"
    );
}
