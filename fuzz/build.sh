#!/usr/bin/env bash
# Builds the fuzz targets with libFuzzer on the STABLE toolchain: the SanitizerCoverage
# instrumentation cargo-fuzz asks for is passed by hand as stable `-C` flags (no sanitizer,
# i.e. cargo-fuzz's `--sanitizer none`). Binaries land in fuzz/target/<host triple>/release/<target>.
set -euo pipefail
cd "$(dirname "$0")"
export RUSTFLAGS="--cfg fuzzing -Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4 \
-Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table \
-Cllvm-args=-sanitizer-coverage-trace-compares -Cdebug-assertions -Coverflow-checks"
export CARGO_TARGET_DIR="$PWD/target"
# an explicit --target keeps the instrumentation off build scripts and proc-macros
cargo build --release --target "$(rustc -vV | sed -n "s/^host: //p")" "$@"
