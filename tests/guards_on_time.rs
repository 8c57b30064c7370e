//! `--max-time` stops a run on time, not at the end of its current piece of work: the
//! quadrature rules stop refining once the thread's deadline passes
//! (`brdfbake::quadrature::budget`), so a laws run whose single albedos take seconds ends
//! within a fraction of a second of its limit.
//!
//! Slack: the run ends after the panel under way (milliseconds here) and process start and
//! exit; 1 s leaves room for a loaded 2-core CI machine, and is below the 0.5 to 1.9 s the
//! runs overran by when the limit was checked between albedos only.

use std::time::{Duration, Instant};

#[path = "common/cli.rs"]
mod cli;

#[test]
fn laws_stops_within_a_second_of_its_limit() {
    let dir = tempfile::tempdir().unwrap();
    // a needle-thin anisotropic lobe at a tolerance it cannot reach quickly: each albedo
    // takes seconds (the full run minutes)
    let limit = 2.0;
    let start = Instant::now();
    let o = cli::run_within(
        dir.path(),
        &[
            "laws",
            "ward:alpha_x=0.001,alpha_y=0.3",
            "--tolerance",
            "1e-10",
            "--albedo-table",
            "16",
            "--max-time",
            &limit.to_string(),
        ],
        Duration::from_secs(120),
    );
    let took = start.elapsed().as_secs_f64();
    cli::assert_fails(
        &o,
        cli::ENV,
        &["stopped at the time limit", "nothing was written"],
        "laws",
    );
    assert!(
        took < limit + 1.0,
        "stopped after {took:.2} s, limit {limit} s"
    );
}

/// Under an address-space limit (`ulimit -v`) a bake that `--max-memory` admits but the
/// limit cannot hold is refused up front (exit 2, naming the limit), where it used to abort
/// with SIGABRT at an allocation; a bake that fits runs.
#[test]
fn a_bake_past_ulimit_v_is_refused_not_aborted() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(
        d.join("big.json"),
        r#"{"schema": "brdfbake.preset/1", "tables": [{"name": "dfg", "kind": "dfg", "layout": "filament",
         "model": {"ndf": "ggx", "masking": "smith-height-correlated"},
         "axes": {"cos_theta_v": {"size": 2048}, "roughness": {"size": 2048, "quantity": "perceptual"}},
         "formats": ["exr", "ktx2", "png", "h"]}]}"#,
    )
    .unwrap();
    let bin = env!("CARGO_BIN_EXE_brdfbake");
    let under_limit = |args: &str| {
        std::process::Command::new("bash")
            .arg("-c")
            .arg(format!("ulimit -v 600000 && exec {bin} {args}"))
            .current_dir(d)
            .env_remove("RAYON_NUM_THREADS")
            .output()
            .unwrap()
    };
    let o = under_limit("bake big.json --out out --max-memory 3G --max-time 3000");
    cli::assert_fails(
        &o,
        cli::INPUT,
        &["address-space limit", "RLIMIT_AS", "ulimit -v"],
        "ulimit -v",
    );
    assert!(!d.join("out").exists());
    let o = under_limit("bake filament-dfg --out out -q");
    assert!(o.status.success(), "{}", cli::stderr(&o));
}
