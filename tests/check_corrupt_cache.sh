#!/usr/bin/env bash
# A cached RTL bench-*.so truncated to 1,000 bytes (a full disk, a killed
# copy) must never be loaded (that crashed cdsim with SIGBUS): regress names
# it as corrupt, with its size and the size it had when built, and rebuilds it.
# The test works on a copy of SOURCE_CACHE (which the test that builds it
# fills), so that the other tests keep their cache.
#   quick: SIGTERM once the rebuild has started: exit 143 within 2 s, no
#          tmp-bench- folder and no process left (a few seconds).
#   full:  the rebuild runs to the end with no mismatch, and a second run
#          reuses it (label long).
# Usage: check_corrupt_cache.sh quick|full CDSIM SOURCE_CACHE WORK REGRESS_ARGS...
set -u -m
mode=$1 cdsim=$2 source=$3 work=$4
shift 4
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
rm -rf "$work" && mkdir -p -m 0700 "$work/cache"
find "$source" -mindepth 1 -maxdepth 1 -type d ! -name 'tmp-*' ! -name 'failed-*' -exec cp -a {} "$work/cache/" \;
# Another test may be building in the source cache right now (the adaptive
# unit's bench, in a tmp-bench-* folder inside its entry): no work folder of
# anyone else's in the copy, so that any left at the end is this regress's.
find "$work/cache" -mindepth 2 -depth -name 'tmp-*' -exec rm -rf {} +
# The source cache holds benches of other units and widths too (the adaptive
# unit's, say), so every bench is truncated: whichever one these arguments
# select must be named with its own size.
benches=()
for bench in "$work"/cache/*/bench-*.so; do [ -f "$bench" ] && benches+=("$bench"); done
[ ${#benches[@]} -gt 0 ] || { echo "FAIL: no bench-*.so in $source (run the test that builds it first)"; exit 1; }
names=()
for bench in "${benches[@]}"; do
  names+=("$(basename "$bench"): 1000 bytes, $(stat -c %s "$bench") when built")
  truncate -s 1000 "$bench"
done
expect="is corrupt \\(($(IFS='|'; echo "${names[*]}"))\\); rebuilding it"

"$cdsim" regress "$@" --rtl-cache "$work/cache" >"$work/log" 2>&1 &
pid=$!
if [ "$mode" = full ]; then
  wait "$pid"; status=$?
  cat "$work/log"
  grep -Eq -- "$expect" "$work/log" || { echo "FAIL: no line /$expect/"; exit 1; }
  [ "$status" -eq 0 ] && grep -q ", 0 mismatches," "$work/log" || { echo "FAIL: exit $status"; exit 1; }
  "$cdsim" regress "$@" --rtl-cache "$work/cache" >"$work/log" 2>&1
  grep -q "^regress: reusing the RTL built for these widths" "$work/log" ||
    { cat "$work/log"; echo "FAIL: the rebuilt bench is not reused"; exit 1; }
  echo PASS; exit 0
fi
until grep -Eq -- "$expect" "$work/log" && grep -q "compiling the bench" "$work/log"; do
  if ! kill -0 "$pid" 2>/dev/null; then
    wait "$pid"
    cat "$work/log"; echo "FAIL: exited with $? before /$expect/ and the bench's rebuild"; exit 1
  fi
  sleep 0.1
done
sleep 1
start=$EPOCHREALTIME
kill -TERM "$pid"
wait "$pid"; status=$?
seconds=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }')
cat "$work/log"
[ "$status" -eq 143 ] || { echo "FAIL: exit status $status, expected 143"; exit 1; }
awk -v s="$seconds" 'BEGIN { exit !(s <= 2) }' || { echo "FAIL: exited $seconds s after SIGTERM"; exit 1; }
left=$(find "$work/cache" -name 'tmp-*')
[ -z "$left" ] || { echo "FAIL: left: $left"; exit 1; }
pgrep -f -- "$work/cache" >"$work/left.pids"
grep -vx "$$" "$work/left.pids" >"$work/left" || true
[ -s "$work/left" ] && { echo "FAIL: processes left:"; cat "$work/left"; exit 1; }
echo "ok: named the truncated bench, started its rebuild, stopped $seconds s after SIGTERM with nothing left"
