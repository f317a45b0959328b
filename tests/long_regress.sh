#!/usr/bin/env bash
# A long random regression sharded over all cores with GNU parallel: N shards
# of `cdsim regress --random TRIANGLES --shard I/N --json`, joined by
# `cdsim merge`, which exits 1 if any shard mismatched or hung. Prints the
# merged figures and the wall time.
# Usage: long_regress.sh CDSIM WORKDIR TRIANGLES SEED DESIGNS REGRESS_ARGS...
set -euo pipefail
cdsim=$1 work=$2 triangles=$3 seed=$4 designs=$5
shift 5
rm -rf "$work" && mkdir -p "$work"
shards=$(nproc)
start=$(date +%s)
export SYSTEMC_DISABLE_COPYRIGHT_MESSAGE=1
# --halt never: every shard runs to its end, so a mismatch in one does not hide the others' figures.
parallel --halt never --jobs "$shards" --line-buffer --tagstring 'shard {}' \
  "$cdsim" regress --random "$triangles" --seed "$seed" --design "$designs" --backpressure 0.3 "$@" \
  --shard {}/"$shards" --json "$work/shard{}.json" '>' "$work/shard{}.log" '2>&1' ::: $(seq 1 "$shards") || true
for i in $(seq 1 "$shards"); do
  [[ -s $work/shard$i.json ]] || { echo "FAIL shard $i wrote no summary:"; tail -20 "$work/shard$i.log"; exit 1; }
done
status=0
"$cdsim" merge "$work"/shard*.json --out "$work/merged.json" || status=$?
/usr/bin/python3 - "$work/merged.json" "$(( $(date +%s) - start ))" "$shards" <<'PY'
import json, sys
m = json.load(open(sys.argv[1]))
print(f"{m['triangles']} triangles in {sys.argv[3]} shards, {m['fragments']} fragments, "
      f"{m['mismatches']} mismatches, {m['hangs']} hangs, RTL cycles {m['rtl_cycles']}, "
      f"model cycles {m['model_cycles']}, clocks {m['clocks']} (model {m['model_clocks']}); wall {sys.argv[2]} s")
PY
exit $status
