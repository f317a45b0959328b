#!/usr/bin/env bash
# Synthesises the unit at narrow, default and (when WIDE SETTINGS are given)
# wide widths (cdsim area, fresh cache) and fails unless each synthesis passes
# its own checks (no divider, latch or unmapped cell: the Yosys script asserts
# them) and the logic area grows narrow < default < wide.
# Usage: check_area.sh CDSIM WORKDIR "NARROW SETTINGS" ["WIDE SETTINGS" [NARROW_CACHE]]
# NARROW_CACHE: a synthesis cache that already holds cd-linear at the narrow
# widths (rtl_synth_design_blocks fills one), so that it is not synthesised twice.
set -euo pipefail
cdsim=$1 work=$2 narrow=$3 wide=${4:-} narrow_cache=${5:-}
rm -rf "$work" && mkdir -p "$work"
area() {  # name, settings...
  local name=$1; shift
  local args=() cache=$work/cache
  [[ $name == narrow && -n $narrow_cache ]] && cache=$narrow_cache
  for s in "$@"; do args+=(--set "$s"); done
  "$cdsim" area --design cd-linear "${args[@]}" --cache "$cache" --json "$work/$name.json"
  grep -o '"logic_area_um2": [0-9.e+]*' "$work/$name.json" | awk '{print $2}'
}
# shellcheck disable=SC2086
a_narrow=$(area narrow $narrow | tail -1)
a_default=$(area default | tail -1)
if [[ -z $wide ]]; then
  echo "logic area: narrow $a_narrow, default $a_default um^2"
  awk -v n="$a_narrow" -v d="$a_default" 'BEGIN { exit !(n > 0 && n < d) }' ||
    { echo "FAIL: the area does not grow narrow < default"; exit 1; }
  echo "PASS"; exit 0
fi
# shellcheck disable=SC2086
a_wide=$(area wide $wide | tail -1)
echo "logic area: narrow $a_narrow, default $a_default, wide $a_wide um^2"
awk -v n="$a_narrow" -v d="$a_default" -v w="$a_wide" 'BEGIN { exit !(n > 0 && n < d && d < w) }' ||
  { echo "FAIL: the area does not grow narrow < default < wide"; exit 1; }
echo "PASS"
