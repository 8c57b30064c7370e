//! BENCHMARKS.md's table of fits against the published ones (`brdfbake::fit::figures`).
//!
//! ```text
//! cargo run --release --example fit_figures [-- --write]
//! ```
//! `--write` replaces BENCHMARKS.md's generated block; `tests/fit_figures.rs` checks it.

use brdfbake::fit::figures::{markdown, rows, BEGIN, END};

fn main() {
    let md = markdown(&rows().expect("the fits"));
    println!("{md}");
    if std::env::args().any(|a| a == "--write") {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/BENCHMARKS.md");
        let text = std::fs::read_to_string(path).expect("BENCHMARKS.md");
        let (a, b) = (
            text.find(BEGIN)
                .expect("BENCHMARKS.md has the begin marker"),
            text.find(END).expect("BENCHMARKS.md has the end marker") + END.len(),
        );
        std::fs::write(path, format!("{}{md}{}", &text[..a], &text[b..])).expect("write");
        eprintln!("BENCHMARKS.md updated");
    }
}
