#!/usr/bin/env bash
# `cdsim regress --set`: widths that no built-in configuration has are verilated
# into a fresh cache on first use and run without a mismatch; a second run
# reuses the cache (and says so) with the same result.
# Usage: check_rtl_cache.sh CDSIM CACHE_DIR REGRESS_ARGS...
set -uo pipefail
cdsim=$1 cache=$2
shift 2
rm -rf "$cache"
regress() {  # the line the run must print, then its summary must show no mismatch
  local expect=$1 out status
  out=$("$cdsim" regress --rtl-cache "$cache" "${@:2}" 2>&1)
  status=$?
  echo "$out"
  [ "$status" -eq 0 ] || { echo "FAIL: exit $status"; exit 1; }
  grep -q "^regress: $expect" <<<"$out" || { echo "FAIL: no line 'regress: $expect'"; exit 1; }
  grep -q ", 0 mismatches," <<<"$out" || { echo "FAIL: no '0 mismatches' summary"; exit 1; }
  grep "mismatches" <<<"$out" | sed 's/, [0-9]* cycles\/s$//'
}
first=$(regress "building the RTL for widths" "$@") || { echo "$first"; exit 1; }
echo "$first"
second=$(regress "reusing the RTL built for these widths" "$@") || { echo "$second"; exit 1; }
echo "$second"
[ "$(tail -1 <<<"$first")" = "$(tail -1 <<<"$second")" ] ||
  { echo "FAIL: the cached run differs: $(tail -1 <<<"$first")"; exit 1; }
echo PASS
