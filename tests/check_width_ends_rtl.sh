#!/usr/bin/env bash
# The RTL at the ends of the width ranges: `regress --random 50` (every design
# of the scan unit in turn, then the adaptive unit) must build and match the
# model with no mismatch.
#   all:  every parameter at its minimum; then every parameter at its maximum,
#         lowered only where `cdsim widths` says the others narrow it (the
#         adaptive leaves' coordinates: adapt_depth at most 14 - subpixel_bits).
#   each: each parameter alone at its minimum and at its maximum (a custom
#         RTL build each: about two hours on 2 cores; label long).
# Usage: check_width_ends_rtl.sh CDSIM RTL_CACHE all|each
set -u
cdsim=$1 cache=$2 mode=$3
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
params=$("$cdsim" widths | awk 'NR > 1 && NF == 0 { exit } NR > 1 { print $1, $3, $4 }')
[ -n "$params" ] || { echo "FAIL: cdsim widths listed no parameter"; exit 1; }
failures=0

regress() {  # label, design, settings...
  local label=$1 design=$2 out status args=()
  shift 2
  for s in "$@"; do args+=(--set "$s"); done
  if ! err=$("$cdsim" widths "${args[@]}" 2>&1 >/dev/null); then
    echo "refused (the model test checks the message): $label: $err"
    return
  fi
  out=$("$cdsim" regress --random 50 --seed 1 --design "$design" "${args[@]}" --rtl-cache "$cache" 2>&1)
  status=$?
  if [ "$status" -eq 0 ] && grep -q ", 0 mismatches," <<<"$out"; then
    echo "ok: $label ($design): $(grep ', 0 mismatches,' <<<"$out" | sed 's/, RTL cycles.*//')"
  else
    echo "FAIL: $label ($design): exit $status"; grep -v '^  ' <<<"$out" | tail -8
    failures=$((failures + 1))
  fi
}

if [ "$mode" = all ]; then
  min=() max=()
  while read -r name lo hi; do
    min+=("$name=$lo")
    case $name in
      # The largest that the other maxima allow (cdsim widths --set ... names them).
      adapt_depth) max+=("adapt_depth=4") ;;
      *) max+=("$name=$hi") ;;
    esac
  done <<<"$params"
  for design in mix adaptive; do
    regress "every parameter at its minimum" "$design" "${min[@]}"
    regress "every parameter at its (narrowed) maximum" "$design" "${max[@]}"
  done
else
  while read -r name lo hi; do
    design=mix
    [[ $name == adapt_* ]] && design=adaptive
    regress "$name=$lo" "$design" "$name=$lo"
    regress "$name=$hi" "$design" "$name=$hi"
  done <<<"$params"
fi
[ "$failures" -eq 0 ] || { echo "FAIL: $failures runs"; exit 1; }
echo PASS
