#!/usr/bin/env bash
# Two cdsim that want the same cache entry: the second must wait for the
# first (flock on the entry's lock file), saying so, instead of building it a
# second time beside it. Starts COMMAND, waits for READY_REGEX (its build has
# begun), starts COMMAND again, and passes when the second says it waits
# while only one work folder exists; both are then stopped with SIGTERM.
# Usage: check_cache_lock.sh READY_REGEX WORK CACHE -- COMMAND...
set -u -m
ready=$1 work=$2 cache=$3
shift 3
[ "$1" = -- ] && shift
rm -rf "$work" && mkdir -p "$work"
"$@" >"$work/first" 2>&1 &
first=$!
until grep -Eq -- "$ready" "$work/first"; do
  kill -0 "$first" 2>/dev/null || { cat "$work/first"; echo "FAIL: the first run ended before /$ready/"; exit 1; }
  sleep 0.1
done
"$@" >"$work/second" 2>&1 &
second=$!
for _ in $(seq 100); do
  grep -q "waiting for another cdsim that builds it" "$work/second" && break
  sleep 0.1
done
builds=$(find "$cache" -mindepth 1 -maxdepth 1 -type d -name 'tmp-*' | wc -l)
kill -TERM "$first" "$second"
wait "$first"; s1=$?
wait "$second"; s2=$?
cat "$work/first" "$work/second"
grep -q "waiting for another cdsim that builds it" "$work/second" ||
  { echo "FAIL: the second run did not wait for the first"; exit 1; }
[ "$builds" -eq 1 ] || { echo "FAIL: $builds builds of one entry at once"; exit 1; }
[ "$s1" -eq 143 ] && [ "$s2" -eq 143 ] || { echo "FAIL: exit statuses $s1 and $s2, expected 143"; exit 1; }
echo "ok: the second run waited for the first; one build at a time"
