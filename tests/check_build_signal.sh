#!/usr/bin/env bash
# A signal in the middle of a cache build (Yosys for area, Verilator and the
# compiler for regress): with INT or TERM, cdsim must exit 128 + the signal's
# number within STOP_SECONDS of it, saying it was interrupted; with KILL it
# dies at once. Either way no process it started may be left (its tools run in
# process groups that it, or their supervisor, kills), and after INT or TERM
# no folder may be left in CACHE (no tmp- work folder, no partial entry).
# After KILL, the work folder that the killed run left is removed by the next
# run of the same command (itself stopped with TERM once it builds).
# Usage: check_build_signal.sh SIGNAL READY_REGEX WORK CACHE -- COMMAND...
# WORK is made afresh; XDG_CACHE_HOME points into it, so that commands without
# a cache option (sweep --area) use a private cache too. COMMAND's output goes
# to WORK/log; READY_REGEX matches the line it prints when the build starts.
set -u -m  # -m: the command runs as a job of its own, with SIGINT not ignored
signal=$1 ready=$2 work=$3 cache=$4
shift 4
[ "$1" = -- ] && shift
stop_seconds=${STOP_SECONDS:-2}
rm -rf "$work" && mkdir -p "$work"
export XDG_CACHE_HOME=$work/xdg

# Starts the command, waits for READY plus 2 s (the tools are busy), sends the
# signal; sets status and seconds (from the signal to the exit).
interrupt() {
  local sig=$1
  shift
  : >"$work/log"
  "$@" >>"$work/log" 2>&1 &
  local pid=$!
  until grep -Eq -- "$ready" "$work/log"; do
    if ! kill -0 "$pid" 2>/dev/null; then
      wait "$pid"
      echo "FAIL: exited with $? before printing /$ready/"; cat "$work/log"; exit 1
    fi
    sleep 0.1
  done
  sleep 2
  kill -0 "$pid" 2>/dev/null || { echo "FAIL: the build ended before the signal"; cat "$work/log"; exit 1; }
  local start=$EPOCHREALTIME
  kill -"$sig" "$pid"
  wait "$pid"; status=$?
  seconds=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }')
}

# No process but this script whose command line names WORK (the tools' do:
# their files are in CACHE), after a short grace for the kernel to reap them.
no_process_left() {
  local i
  for i in $(seq 20); do
    pgrep -f -- "$work" >"$work/left.pids"
    grep -vx "$$" "$work/left.pids" >"$work/left" || true
    [ -s "$work/left" ] || return 0
    sleep 0.1
  done
  echo "FAIL: processes left after the $1:"
  while read -r p; do ps -o pid=,ppid=,args= -p "$p"; done <"$work/left"
  exit 1
}

no_folder_left() {
  local left
  left=$(find "$cache" -mindepth 1 -maxdepth 1 -type d 2>/dev/null)
  [ -z "$left" ] || { echo "FAIL: left in $cache after the $1:"; echo "$left"; exit 1; }
}

if [ "$signal" = KILL ]; then
  interrupt KILL "$@"
  cat "$work/log"
  [ "$status" -eq 137 ] || { echo "FAIL: exit status $status after SIGKILL"; exit 1; }
  no_process_left SIGKILL
  killed=$(find "$cache" -mindepth 1 -maxdepth 1 -type d -name 'tmp-*')
  echo "left by the killed run: ${killed:-nothing}"
  signal=TERM  # the next run clears what the killed one left
fi
interrupt "$signal" "$@"
cat "$work/log"
expected=$((128 + $(kill -l "$signal")))
[ "$status" -eq "$expected" ] || { echo "FAIL: exit status $status, expected $expected"; exit 1; }
grep -q "interrupted by SIG$signal" "$work/log" || { echo "FAIL: no 'interrupted by SIG$signal' message"; exit 1; }
awk -v s="$seconds" -v m="$stop_seconds" 'BEGIN { exit !(s <= m) }' ||
  { echo "FAIL: exited $seconds s after SIG$signal (at most $stop_seconds)"; exit 1; }
no_process_left "SIG$signal"
no_folder_left "SIG$signal"
echo "ok: exit $status $seconds s after SIG$signal, no process and no partial entry left"
