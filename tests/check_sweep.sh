#!/usr/bin/env bash
# Usage: check_sweep.sh CDSIM OUT_DIR: runs a small sweep and checks its CSV and JSON.
set -euo pipefail
cdsim=$1 out=$2 data=$(dirname "$0")/data
rm -rf "$out"
"$cdsim" sweep --scene "$data/small_scene.tri" --design cd-linear,kim-pipe,affine-sub8 \
  --set g_frac=8:12:2 --set kim_frac=2,6 --out "$out" --jobs 2
rows=$(($(wc -l < "$out/sweep.csv") - 1))
# 3 designs x 3 g_frac values x 2 kim_frac values
[ "$rows" -eq 18 ] || { echo "FAIL: expected 18 rows, found $rows"; exit 1; }
head -1 "$out/sweep.csv" | grep -q "design,subpixel_bits" || { echo "FAIL: header"; exit 1; }
for column in cycles pixels_per_clock table_bits error_mean error_rms error_p99 error_max footprint_max texel_mismatch; do
  head -1 "$out/sweep.csv" | tr ',' '\n' | grep -qx "$column" || { echo "FAIL: no column $column"; exit 1; }
done
/usr/bin/python3 - "$out" <<'PY'
import json, sys
j = json.load(open(sys.argv[1] + "/sweep.json"))
rows = j["rows"]
assert len(rows) == 18, len(rows)
assert {r["name"] for r in rows} == {"cd-linear", "kim-pipe", "affine-sub8"}
assert all(r["pixels"] > 0 and r["cycles"] >= r["pixels"] for r in rows)
kim = sorted((r["widths"]["kim_frac"], r["error"]["mean"]) for r in rows if r["name"] == "kim-pipe")
assert kim[0][1] > kim[-1][1], "more fraction bits must lower the Kim-style error"
print("sweep ok:", len(rows), "rows")
PY
