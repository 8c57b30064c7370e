//! The 64² GGX LTC table judged on lights it was not tuned on: brdfbake's fit against Heitz's
//! published `ltc.inc` on draws of the stated light distribution and its variants
//! (`brdfbake::table::ltc_heldout`), as the relative error of the lit value against a
//! quadrature ground truth.
//!
//! ```text
//! cargo run --release --example ltc_heldout [-- --write] [--energy L --floor F --probe W --point W]
//! ```
//! `--write` replaces BENCHMARKS.md's generated block (default fit options only);
//! `tests/ltc_heldout.rs` checks it. The other flags try other fit options (printed only).

use brdfbake::kernels::ltc_fit::LtcFitOptions;
use brdfbake::table::ltc_heldout::{held_out_rows, markdown, BEGIN, END};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |f: &str| {
        args.iter()
            .position(|a| a == f)
            .and_then(|i| args.get(i + 1))
            .map(|v| {
                v.parse::<f64>()
                    .unwrap_or_else(|_| panic!("{f} takes a number"))
            })
    };
    let mut opts = LtcFitOptions::default();
    let mut changed = false;
    for (flag, field) in [
        ("--energy", &mut opts.energy_weight),
        ("--floor", &mut opts.floor),
        ("--probe", &mut opts.probe_weight),
        ("--point", &mut opts.point_weight),
    ] {
        if let Some(v) = value(flag) {
            *field = v;
            changed = true;
        }
    }
    let rows = held_out_rows(include_str!("../tests/data/ltc/heitz_ltc.inc"), &opts)
        .expect("the fit and the ground truth");
    let md = markdown(&rows);
    println!("{md}");
    if args.iter().any(|a| a == "--write") {
        assert!(!changed, "--write takes the default fit options only");
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
