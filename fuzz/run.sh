#!/usr/bin/env bash
# Runs one fuzz target for SECONDS (default 660) at low priority:
#   fuzz/run.sh preset 660
# New inputs go to fuzz/corpus/<target>/, crashes to fuzz/artifacts/<target>/, the log to
# fuzz/logs/<target>.log (its last lines are libFuzzer's final stats).
set -euo pipefail
cd "$(dirname "$0")"
t="$1"; secs="${2:-660}"
bin="target/$(rustc -vV | sed -n 's/^host: //p')/release/$t"
mkdir -p "corpus/$t" "artifacts/$t" logs
# no Rust backtrace: symbolizing one under load outlasted -timeout and hid the crash input
export RUST_BACKTRACE=0
exec nice -n 19 "$bin" "corpus/$t" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="artifacts/$t/" > "logs/$t.log" 2>&1
