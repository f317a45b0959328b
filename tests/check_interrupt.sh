#!/usr/bin/env bash
# Usage: check_interrupt.sh SIGNAL READY_REGEX WORK_DIR -- COMMAND...
# Starts COMMAND, whose outputs go into WORK_DIR/out (the caller's arguments
# say so), waits until its stdout matches READY_REGEX (it has begun the long
# part), sends SIGNAL (INT or TERM), and passes when it stops with exit status
# 128 + the signal's number, says it was interrupted, and has left nothing in
# WORK_DIR/out but its lock file: no partial output, no temporary file.
# Nothing is timed: the script waits for events, ctest's timeout bounds it.
set -u -m  # -m: the command runs as a job of its own, with SIGINT not ignored
signal=$1 ready=$2 work=$3
shift 3
[ "$1" = -- ] && shift
rm -rf "$work" && mkdir -p "$work/out"
"$@" >"$work/stdout" 2>"$work/stderr" &
pid=$!
until grep -Eq -- "$ready" "$work/stdout"; do
  if ! kill -0 "$pid" 2>/dev/null; then
    wait "$pid"
    echo "FAIL: exited with $? before printing /$ready/"; cat "$work/stdout" "$work/stderr"; exit 1
  fi
  sleep 0.1
done
kill -"$signal" "$pid"
wait "$pid"; status=$?
cat "$work/stderr"
expected=$((128 + $(kill -l "$signal")))
[ "$status" -eq "$expected" ] || { echo "FAIL: exit status $status, expected $expected"; exit 1; }
grep -q "interrupted by SIG$signal" "$work/stderr" || { echo "FAIL: no 'interrupted by SIG$signal' message"; exit 1; }
left=$(find "$work/out" -mindepth 1 ! -name .cdsim.lock)
[ -z "$left" ] || { echo "FAIL: left in the output folder:"; echo "$left"; exit 1; }
echo "ok: exit $status, nothing partial left"
