#!/usr/bin/env bash
# run evaluates its designs in parallel (--jobs), and a design alone measures
# its error on every core: one thread and several must print and write the
# same (the tables, the JSON, the first design's dump, every design's flagged
# triangles in the designs' order).
# Usage: check_run_jobs.sh CDSIM WORKDIR SCENE
set -euo pipefail
cdsim=$1 work=$2 scene=$3
rm -rf "$work" && mkdir -p "$work"
designs=cd-linear,divide,cd-persp,affine,kim-pipe,adaptive
for j in 1 4; do
  mkdir -p "$work/$j"
  "$cdsim" run --scene "$scene" --design "$designs" --set out_int=8 --jobs "$j" --dump "$work/$j/dump.csv" \
    --flagged "$work/$j/flagged.csv" --json "$work/$j/run.json" 2>/dev/null |
    grep -v -E '^(build|wrote) ' > "$work/$j/run.txt"
done
# One design, its error measurement on three threads.
for j in 1 3; do
  mkdir -p "$work/single$j"
  "$cdsim" run --scene "$scene" --design cd-linear --set out_int=8 --jobs "$j" --dump "$work/single$j/dump.csv" \
    --flagged "$work/single$j/flagged.csv" --json "$work/single$j/run.json" 2>/dev/null |
    grep -v -E '^(build|wrote) ' > "$work/single$j/run.txt"
done
same() {  # folder, folder
  for f in run.txt dump.csv flagged.csv; do
    cmp "$1/$f" "$2/$f" || { echo "FAIL: $f differs between $1 and $2"; exit 1; }
  done
  diff <(grep -v '"build"' "$1/run.json") <(grep -v '"build"' "$2/run.json") ||
    { echo "FAIL: run.json differs between $1 and $2"; exit 1; }
}
same "$work/1" "$work/4"
same "$work/single1" "$work/single3"
# The check has teeth only if several designs flag triangles: their rows
# come in the designs' order.
order=$(cut -d, -f1 "$work/1/flagged.csv" | tail -n +2 | uniq | paste -sd, -)
echo "flagged rows by design: $order"
[[ $order == *,* ]] || { echo "FAIL: fewer than two designs flag triangles"; exit 1; }
expected=$(tr , '\n' <<< "$designs" | grep -x -F -f <(tr , '\n' <<< "$order") | paste -sd, -)
[[ $order == "$expected" ]] || { echo "FAIL: flagged rows not in the designs' order ($order, expected $expected)"; exit 1; }
echo PASS
