//! Rewrites the generated engine tables of README.md and docs/engines.md from `compare`
//! over tests/data/engines (the manifest there), or, without `--write`, prints them:
//!
//!     cargo run --release --example engine_figures -- --write
//!
//! tests/doc_figures.rs renders the same blocks and fails when the docs differ.

#[path = "../tests/common/engine_figures.rs"]
mod engine_figures;

fn main() {
    let write = std::env::args().any(|a| a == "--write");
    let cs = engine_figures::comparisons();
    for (path, text) in engine_figures::generated_docs(&cs) {
        if write {
            std::fs::write(engine_figures::root().join(path), text).unwrap();
            println!("wrote {path}");
        } else {
            println!("==> {path}\n{text}");
        }
    }
}
