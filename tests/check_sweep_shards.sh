#!/usr/bin/env bash
# A sweep run as shards under GNU parallel, then joined by cdsim merge, must
# write the very bytes the whole sweep writes: with 3 shards, and with more
# shards than configurations (some shards empty, as a fixed-size job array
# gives). Usage: check_sweep_shards.sh CDSIM WORKDIR SCENE
set -euo pipefail
cdsim=$1 work=$2 scene=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"
sweep=(sweep --scene "$scene" --design cd-linear,divide,kim-pipe --set g_frac=8:12 --set out_frac=4,8)
"$cdsim" "${sweep[@]}" --out whole > whole.txt
for n in 3 40; do
  parallel --halt now,fail=1 "$cdsim" "${sweep[@]}" --shard {}/$n --out shard$n-{} '>' shard$n-{}.txt \
    ::: $(seq 1 $n)
  "$cdsim" merge $(seq -f "shard$n-%g" 1 $n) --out merged$n > merged$n.txt
  cmp whole/sweep.csv merged$n/sweep.csv
  cmp whole/sweep.json merged$n/sweep.json
  rows=$(($(wc -l < whole/sweep.csv) - 1))
  held=0
  for i in $(seq 1 $n); do held=$((held + $(wc -l < shard$n-$i/sweep.csv) - 1)); done
  [[ $held == "$rows" ]] || { echo "FAIL: $n shards hold $held rows, the whole sweep $rows"; exit 1; }
  echo "ok   $n shards under GNU parallel: $rows configurations, merged byte for byte"
done
# Refused, naming what is wrong: a whole sweep, a missing shard, a shard twice,
# shards of different sweeps.
refuse() {
  local want=$1; shift
  if out=$("$cdsim" merge "$@" --out refused 2>&1); then echo "FAIL: merge $* succeeded"; exit 1; fi
  [[ $out == *"$want"* ]] || { echo "FAIL: merge $*: '$out' does not say '$want'"; exit 1; }
  echo "ok   merge $*: $out"
}
refuse "not a shard of a sweep" whole shard3-1
refuse "shard 3/3 missing" shard3-1 shard3-2
refuse "are both shard 2/3" shard3-1 shard3-2 shard3-2 shard3-3
refuse "shards of different sweeps" shard3-1 shard3-2 shard40-3
