#!/usr/bin/env bash
# The correction adder's pipeline registers cut cd-persp's path (issue 42,
# item 7), and choose takes them for a clock (item 5). At narrow widths:
#  1. cdsim area of cd-persp at correction_stages 0, 1 and 2: the worst path
#     ending in the correction adder or the control (the unit's sticky flags,
#     where the combinational adder's path ends) falls at each step; the
#     adder gains flip-flops at each; the model counts a cycle more a
#     triangle walked through the table at each (run on the small scene).
#  2. choose --design cd-persp on the small scene at 0.1 texels without a
#     clock, then with --clock-mhz just above the f_max it found, both with
#     the fully parallel setup engine, so that the adder, not a shared
#     multiplier, sets the clock (at 1 texel the widths choose sizes leave
#     the adder short and the setup engine sets it: no register to add): the
#     second run synthesises cd-persp again with correction_stages=2 and
#     takes it, with a higher f_max.
# Usage: check_correction_timing.sh CDSIM WORKDIR "NARROW SETTINGS"
set -euo pipefail
cdsim=$1 work=$2 narrow=$3
rm -rf "$work" && mkdir -p "$work/cache"
args=()
for s in $narrow; do args+=(--set "$s"); done
scene=$(dirname "$0")/data/small_scene.tri
for stages in 0 1 2; do
  "$cdsim" area --design cd-persp "${args[@]}" --set correction_stages=$stages --cache "$work/cache" \
    --json "$work/area_$stages.json" > /dev/null
  "$cdsim" run --scene "$scene" --design cd-persp "${args[@]}" --set correction_stages=$stages \
    --json "$work/run_$stages.json" > /dev/null
done
"$cdsim" choose "$scene" --design cd-persp --max-error 0.1 --no-verify --area-cache "$work/cache" \
  --set setup_multipliers=0 --json "$work/choose_free.json" > "$work/choose_free.txt"
fmax=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['ranking'][0]['fmax_mhz'])" \
  "$work/choose_free.json")
clock=$(/usr/bin/python3 -c "print(round(float('$fmax') + 0.1, 1))")
"$cdsim" choose "$scene" --design cd-persp --max-error 0.1 --no-verify --area-cache "$work/cache" \
  --set setup_multipliers=0 --clock-mhz "$clock" --json "$work/choose_clock.json" > "$work/choose_clock.txt" 2> "$work/choose_clock.err"

/usr/bin/python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
area = {n: json.load(open(f"{work}/area_{n}.json")) for n in (0, 1, 2)}
def block(n, name):
    return next(b for b in area[n]["blocks"] if b["name"] == name)
path = {n: max(block(n, "correction adder")["critical_path_ns"] or 0, block(n, "control")["critical_path_ns"] or 0)
        for n in (0, 1, 2)}
flops = {n: block(n, "correction adder")["flops"] for n in (0, 1, 2)}
print("paths into the correction adder and the control:", {n: round(p, 2) for n, p in path.items()},
      "adder flip-flops:", flops)
expect(path[1] < path[0], f"one register cuts the path: {path[0]:.2f} -> {path[1]:.2f} ns")
expect(path[2] < path[1], f"the second cuts it again: {path[1]:.2f} -> {path[2]:.2f} ns")
expect(flops[0] < flops[1] < flops[2], f"each register is flip-flops: {flops}")
run = {n: json.load(open(f"{work}/run_{n}.json"))["designs"][0] for n in (0, 1, 2)}
cycles = {n: run[n]["cycles"] for n in (0, 1, 2)}
expect(cycles[0] < cycles[1] < cycles[2], f"the model counts each register's cycle: {cycles}")
expect(run[0]["error"] == run[2]["error"], "the values do not change")
free = json.load(open(f"{work}/choose_free.json"))["ranking"][0]
clocked = json.load(open(f"{work}/choose_clock.json"))["ranking"][0]
expect(free["widths"].get("correction_stages", 0) == 0, "without a clock choose keeps the adder combinational")
expect(clocked["widths"].get("correction_stages") == 2,
       f"below the clock it takes correction_stages=2 ({clocked['widths'].get('correction_stages')})")
expect(clocked["fmax_mhz"] > free["fmax_mhz"], f"with a higher f_max: {free['fmax_mhz']} -> {clocked['fmax_mhz']} MHz")
expect("synthesised again with correction_stages=2" in open(f"{work}/choose_clock.err").read(),
       "choose says it synthesised the design again, and with what")
sys.exit(1 if failures else 0)
PY
echo PASS
