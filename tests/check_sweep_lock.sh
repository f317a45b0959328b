#!/usr/bin/env bash
# Usage: check_sweep_lock.sh CDSIM WORK_DIR
# Two sweeps into one folder: while one runs (it holds DIR/.cdsim.lock), a
# second is refused naming the folder and writes nothing. SIGINT stops the
# first with exit status 130 and no sweep.csv or sweep.json; once it has
# ended the folder is free again. An interrupted sweep over a finished one
# leaves the finished one's files byte for byte.
# Nothing is timed: the script waits for events, ctest's timeout bounds it.
set -u -m
cdsim=$1 work=$2 data=$(dirname "$0")/data
out=$work/out
rm -rf "$work" && mkdir -p "$work"
small=(sweep --scene "$data/small_scene.tri" --design cd-linear --set g_frac=8:12:2 --out "$out" --jobs 1)
# Long enough to be running when the second starts: 12 designs x 29 values on the default scene.
long=(sweep --scene default --set g_frac=2:30 --out "$out" --jobs 1)

start_long() {
  "$cdsim" "${long[@]}" >"$work/long.stdout" 2>"$work/long.stderr" &
  pid=$!
  until grep -q "^threads:" "$work/long.stdout"; do  # printed once the lock is held
    kill -0 "$pid" 2>/dev/null || { echo "FAIL: the long sweep ended early"; cat "$work/long.stderr"; exit 1; }
    sleep 0.1
  done
}
interrupt_long() {
  kill -INT "$pid"
  wait "$pid"; status=$?
  [ "$status" -eq 130 ] || { echo "FAIL: interrupted sweep exit $status, expected 130"; cat "$work/long.stderr"; exit 1; }
  grep -q "interrupted by SIGINT" "$work/long.stderr" || { echo "FAIL: no interrupt message"; exit 1; }
  tmp=$(find "$out" -name '*.tmp')
  [ -z "$tmp" ] || { echo "FAIL: temporary files left: $tmp"; exit 1; }
}

# 1. A second sweep into a locked folder is refused at once and writes nothing.
start_long
if "$cdsim" "${small[@]}" >"$work/second.stdout" 2>"$work/second.stderr"; then
  echo "FAIL: the second sweep into a locked folder succeeded"; exit 1
fi
grep -q "another cdsim run is writing into this folder" "$work/second.stderr" ||
  { echo "FAIL: message:"; cat "$work/second.stderr"; exit 1; }
grep -qF "$out" "$work/second.stderr" || { echo "FAIL: the message does not name the folder"; exit 1; }
[ ! -e "$out/sweep.csv" ] && [ ! -e "$out/sweep.json" ] || { echo "FAIL: output appeared"; exit 1; }

# 2. SIGINT: exit 130, no output at all.
interrupt_long
[ ! -e "$out/sweep.csv" ] && [ ! -e "$out/sweep.json" ] || { echo "FAIL: an interrupted sweep wrote output"; exit 1; }

# 3. The lock went with the process: the folder takes a sweep again.
"$cdsim" "${small[@]}" >"$work/third.stdout" 2>"$work/third.stderr" ||
  { echo "FAIL: sweep after the lock was released"; cat "$work/third.stderr"; exit 1; }
/usr/bin/python3 -c "import json, sys; assert len(json.load(open(sys.argv[1]))['rows']) == 3" "$out/sweep.json" ||
  { echo "FAIL: sweep.json"; exit 1; }
before=$(md5sum "$out/sweep.csv" "$out/sweep.json" | cut -d' ' -f1)

# 4. An interrupted sweep over finished files leaves them as they were.
start_long
interrupt_long
after=$(md5sum "$out/sweep.csv" "$out/sweep.json" | cut -d' ' -f1)
[ "$before" = "$after" ] || { echo "FAIL: the interrupted sweep changed the previous files"; exit 1; }
echo "ok: lock refused the second sweep, SIGINT left no partial file"
