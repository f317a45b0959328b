#!/usr/bin/env bash
# RTL coverage over the CI coverage set (docs/coverage.md): narrow widths on
# random triangles of the thirteen fast designs and on the hard cases with all
# seventeen designs of the scan unit mixed, and with early_walk on the
# constant-depth designs,
# with back-pressure, each run adding its data to one folder.
# Fails if the line coverage of rtl/ is below MIN_LINES percent, if a design's
# or an FSM state's cover point is never hit, or if the lcov and HTML reports
# are missing; and checks that `cdsim coverage` refuses a folder without data.
# SCALE (default 1) multiplies the random triangles; at 1 (CI) the coverage
# build has no toggle points (regress --no-toggle: several times quicker to
# build and run); above 1 (scripts/test --long) it has them, and default and
# wide widths, the default scene and the adaptive design's unit are added.
# Usage: check_rtl_coverage.sh CDSIM WORKDIR RTL_CACHE MIN_LINES [SCALE]
set -euo pipefail
cdsim=$1 work=$2 cache=$3 min_lines=$4 scale=${5:-1}
rm -rf "$work" && mkdir -p "$work/empty"
fast=cd-none,cd-linear,cd-dense2,cd-dense4,cd-dense2-linear,cd-persp,divide,affine-sub16,affine-sub8,quad-sub16,quad-sub8,quad-sub32,affine
toggle=()
((scale > 1)) || toggle=(--no-toggle)
run() { "$cdsim" regress --backpressure 0.3 --rtl-cache "$cache" --coverage "$work/cov" "${toggle[@]}" "$@" \
          > "$work/run.log" 2>&1 || { cat "$work/run.log"; echo "FAIL regress $*"; exit 1; }
        echo "regress $*:"; grep -E "mismatches|^  (line|branch|toggle|user) " "$work/run.log"; }
run --widths narrow --random $((300 * scale)) --seed 3 --design $fast
run --widths narrow --scene hard:all --design mix
# early_walk (a coverage build of its own): bands walked while they are filled,
# with the setup engine on one shared 8 x 8 multiplier.
run --widths narrow --set early_walk=1 --set setup_multipliers=1 --set setup_mul_bits=8 --random $((300 * scale)) --seed 7 \
    --design cd-none,cd-linear,cd-dense2,cd-dense4,cd-dense2-linear,cd-persp
runs=3
if ((scale > 1)); then
  # The Kim designs cost tens of thousands of cycles a random triangle: fewer of them.
  run --widths narrow --random $((2 * scale)) --seed 4 --design kim-iter,kim-pipe
  run --widths default --random $((30 * scale)) --seed 5 --design $fast
  run --widths wide --random $((10 * scale)) --seed 6 --design $fast
  run --widths narrow --scene default --design mix
  # The adaptive design's unit (a coverage build of its own: split engine and leaf unit).
  run --widths narrow --random $((100 * scale)) --seed 8 --design adaptive
  runs=8
fi
"$cdsim" coverage "$work/cov" --min-lines "$min_lines"

if "$cdsim" coverage "$work/empty" > "$work/empty.log" 2>&1; then echo "FAIL coverage accepted a folder without data"; exit 1; fi
grep -q "no coverage data" "$work/empty.log" || { cat "$work/empty.log"; echo "FAIL no message"; exit 1; }

/usr/bin/python3 - "$work/cov" "$runs" "$scale" <<'PY'
import json, os, sys
d, runs, scale = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
cov = json.load(open(f"{d}/coverage.json"))
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
expect(cov["runs"] == runs, f"{runs} runs merged")
# c_front_fill_held needs setup_fifo_depth 1 (the wide widths): the long set only.
uncovered = {u["point"] for u in cov["uncovered"] if u["type"] == "user"}
for p in ["c_state_" + s for s in ("idle", "fill_wait", "init", "column", "pixel", "scan", "record", "drain")] + \
         ["c_front_setup", "c_front_offer", "c_fill_filling", "c_fill_band_wait"] + \
         ["c_setup_during_walk", "c_fill_during_walk", "c_band_filled_ahead", "c_take_at_record",
          "c_hold_in_setup", "c_walk_during_own_fill", "c_walk_starved"] + \
         (["c_front_fill_held"] if scale > 1 else []) + \
         ["c_design_" + s for s in ("cd_none", "cd_linear", "cd_dense2", "cd_dense4", "cd_dense2_linear", "divide",
                                    "kim_iter", "kim_pipe", "affine_sub16", "affine_sub8", "quad_sub16",
                                    "quad_sub8", "quad_sub32", "affine", "cd_persp", "fallback")] + \
         ["c_fragment_stall", "c_flag_banded", "c_flag_table_saturated", "c_flag_output_saturated",
          "c_x_major", "c_y_major"]:
    expect(p not in uncovered, f"cover point {p} hit")
if scale > 1:
    expect(cov["rtl"].get("toggle", {}).get("total", 0) > 0, "toggle points counted")
else:
    expect("toggle" not in cov["rtl"], "no toggle points in a --no-toggle build")
info = open(f"{d}/coverage.info").read()
expect("SF:" in info and "/rtl/cd_scan_unit.sv" in info, "lcov .info names the RTL sources")
expect(os.path.exists(f"{d}/html/index.html"), "genhtml report")
sys.exit(1 if failures else 0)
PY
