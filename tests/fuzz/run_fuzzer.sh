#!/usr/bin/env bash
# Usage: run_fuzzer.sh FUZZER WORK_DIR SECONDS SEED_FILE...
# Runs one libFuzzer target for SECONDS on a fresh copy of the seed files (the
# corpus it grows stays in WORK_DIR/corpus), then prints the executions done.
# Fails when the fuzzer finds a crash, a leak, a timeout or an out-of-memory;
# the reproducer is left in WORK_DIR.
set -euo pipefail
fuzzer=$1 work=$2 seconds=$3
shift 3
mkdir -p "$work/corpus"
cp -f "$@" "$work/corpus/"
cd "$work"
status=0
"$fuzzer" -max_total_time="$seconds" -max_len=16384 -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 corpus >fuzz.log 2>&1 || status=$?
grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|^Done" fuzz.log || true
if [ "$status" -ne 0 ]; then
  tail -n 60 fuzz.log
  echo "FAIL: $(basename "$fuzzer") exited with $status; reproducer in $work"
  exit 1
fi
