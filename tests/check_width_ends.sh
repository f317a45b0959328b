#!/usr/bin/env bash
# Every range that `cdsim widths` lists is legal at both ends: each parameter
# at its minimum and at its maximum, alone, and every parameter at its minimum
# (then at its maximum) together, runs the model on a small scene (every
# design). Where the other parameters narrow a range (validate's checks across
# parameters), the refusal must name the limit, and `cdsim widths` at the
# same other values must list that parameter's narrower end.
# Usage: check_width_ends.sh CDSIM SCENE
set -u
cdsim=$1 scene=$2
failures=0
params=$("$cdsim" widths | awk 'NR > 1 && NF == 0 { exit } NR > 1 { print $1, $3, $4 }')
[ -n "$params" ] || { echo "FAIL: cdsim widths listed no parameter"; exit 1; }
narrowed=$("$cdsim" widths | sed -n '/^ranges that the other parameters/,/^$/p')

try() {  # label, settings...
  local label=$1 out status args=()
  shift
  for s in "$@"; do args+=(--set "$s"); done
  out=$("$cdsim" run --scene "$scene" "${args[@]}" 2>&1)
  status=$?
  if [ "$status" -eq 0 ]; then
    echo "ok: $label runs"
    return 0
  fi
  if grep -Eq "limit|at most|at least|exceeds|needs" <<<"$out" && [ "$status" -eq 2 ]; then
    echo "refused: $label: $(tail -1 <<<"$out")"
    return 3
  fi
  echo "FAIL: $label: exit $status"; tail -5 <<<"$out"
  failures=$((failures + 1))
  return 1
}

all_min=() all_max=()
while read -r name lo hi; do
  all_min+=("$name=$lo") all_max+=("$name=$hi")
  try "$name=$lo" "$name=$lo"
  [ $? -eq 3 ] && ! grep -q "^  $name at least" <<<"$narrowed" &&
    { echo "FAIL: $name=$lo is refused but cdsim widths lists no narrower minimum for it"; failures=$((failures + 1)); }
  try "$name=$hi" "$name=$hi"
  [ $? -eq 3 ] && ! grep -q "^  $name at most" <<<"$narrowed" &&
    { echo "FAIL: $name=$hi is refused but cdsim widths lists no narrower maximum for it"; failures=$((failures + 1)); }
done <<<"$params"
try "every parameter at its minimum" "${all_min[@]}"
[ $? -eq 3 ] && { echo "FAIL: the minima are refused together"; failures=$((failures + 1)); }
# Together the maxima exceed what the adaptive leaves' coordinates hold
# (subpixel_bits + adapt_depth <= 14); the refusal names the limit (try).
try "every parameter at its maximum" "${all_max[@]}"
echo "$narrowed"
[ "$failures" -eq 0 ] || { echo "FAIL: $failures cases"; exit 1; }
echo PASS
