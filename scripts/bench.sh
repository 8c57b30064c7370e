#!/usr/bin/env bash
# Bake benchmark (issue 5): builds the release binary and the runner (examples/bench.rs),
# then bakes every default preset from a cold process (median of 5), filament-dfg at 512²
# on 1 and 2 threads, and every preset together, and prints ONE markdown table (preset,
# table, size, threads, wall ms, CPU ms, evaluations, evaluations/s, estimated and measured
# max error, peak RSS) followed by the issue's targets. Progress goes to stderr.
#
#   scripts/bench.sh                      # everything (10–20 s on 2 cores once built)
#   scripts/bench.sh --no-large           # the presets only
#   scripts/bench.sh --runs 3 --no-error  # faster: fewer runs, no reference integrals
#   scripts/bench.sh presets/filament-dfg.json
#
# Options are passed to the runner; see the header of examples/bench.rs. Run it on an idle
# machine: wall times are medians, but other load inflates them (the CPU ms column less so).
# Outputs go to target/bench/ (scratch).
set -euo pipefail
cd "$(dirname "$0")/.."
# The runner is an example, so cargo builds the dev-dependencies with it, and one of them
# (libktx-rs-sys, the tests' KTX2 judge) builds Khronos' C sources with cmake: the judges'
# venv of scripts/test provides it (set up here if missing).
eval "$(scripts/test --setup-only)"
cargo build --release --quiet --bin brdfbake --example bench
exec target/release/examples/bench --bin target/release/brdfbake "$@"
