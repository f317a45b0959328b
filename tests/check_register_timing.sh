#!/usr/bin/env bash
# A pipelining knob's registers cut its block's path (issue 42, item 7), and
# choose takes them for a clock (item 5). At narrow widths:
#  1. cdsim area of DESIGN at each of VALUES of KNOB: the worst path ending in
#     the BLOCKS (comma-separated, the longest counts) falls at each step;
#     the first block gains flip-flops at each; the model counts more cycles
#     at each (run on the small scene: the first triangle's setup and the
#     last one's drain are never hidden) and the values do not change.
#  2. choose --design DESIGN on the small scene at MAX_ERROR texels without a
#     clock (KNOB stays at its first value), then with --clock-mhz just above
#     the f_max it found, both with the fully parallel setup engine: the
#     second run synthesises DESIGN again with KNOB at its last value and
#     takes it, with a higher f_max. MAX_ERROR is one at which choose's sized
#     widths leave BLOCKS on the critical path (see the tests that call it).
# Usage: check_register_timing.sh CDSIM WORKDIR "NARROW SETTINGS" DESIGN KNOB "VALUES" BLOCKS MAX_ERROR
set -euo pipefail
cdsim=$1 work=$2 narrow=$3 design=$4 knob=$5 values=$6 blocks=$7 max_error=$8
rm -rf "$work" && mkdir -p "$work/cache"
args=()
for s in $narrow; do args+=(--set "$s"); done
scene=$(dirname "$0")/data/small_scene.tri
for value in $values; do
  "$cdsim" area --design "$design" "${args[@]}" --set "$knob=$value" --cache "$work/cache" \
    --json "$work/area_$value.json" > /dev/null
  "$cdsim" run --scene "$scene" --design "$design" "${args[@]}" --set "$knob=$value" \
    --json "$work/run_$value.json" > /dev/null
done
choose=("$cdsim" choose "$scene" --design "$design" --max-error "$max_error" --no-verify --area-cache "$work/cache"
        --set setup_multipliers=0)
"${choose[@]}" --json "$work/choose_free.json" > "$work/choose_free.txt"
fmax=$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['ranking'][0]['fmax_mhz'])" \
  "$work/choose_free.json")
clock=$(/usr/bin/python3 -c "print(round(float('$fmax') + 0.1, 1))")
"${choose[@]}" --clock-mhz "$clock" --json "$work/choose_clock.json" > "$work/choose_clock.txt" \
  2> "$work/choose_clock.err"

/usr/bin/python3 - "$work" "$knob" "$values" "$blocks" <<'PY'
import json, sys
work, knob, blocks = sys.argv[1], sys.argv[2], sys.argv[4].split(",")
values = [int(v) for v in sys.argv[3].split()]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
area = {v: json.load(open(f"{work}/area_{v}.json")) for v in values}
def block(v, name):
    return next(b for b in area[v]["blocks"] if b["name"] == name)
path = {v: max(block(v, name)["critical_path_ns"] or 0 for name in blocks) for v in values}
flops = {v: block(v, blocks[0])["flops"] for v in values}
print(f"{knob}: paths into {', '.join(blocks)}:", {v: round(p, 2) for v, p in path.items()},
      f"{blocks[0]} flip-flops:", flops)
runs = {v: json.load(open(f"{work}/run_{v}.json"))["designs"][0] for v in values}
for a, b in zip(values, values[1:]):
    expect(path[b] < path[a], f"{knob} {a} -> {b} cuts the path: {path[a]:.2f} -> {path[b]:.2f} ns")
    expect(flops[a] < flops[b], f"{knob} {a} -> {b} is flip-flops: {flops[a]} -> {flops[b]}")
    expect(runs[a]["cycles"] < runs[b]["cycles"],
           f"{knob} {a} -> {b}: the model counts the cycles: {runs[a]['cycles']} -> {runs[b]['cycles']}")
    expect(runs[a]["error"] == runs[b]["error"], f"{knob} {a} -> {b}: the values do not change")
free = json.load(open(f"{work}/choose_free.json"))["ranking"][0]
clocked = json.load(open(f"{work}/choose_clock.json"))["ranking"][0]
first, last = values[0], values[-1]
expect(free["widths"].get(knob, first) == first, f"without a clock choose keeps {knob}={first}")
expect(clocked["widths"].get(knob) == last, f"below the clock it takes {knob}={last} ({clocked['widths'].get(knob)})")
expect(clocked["fmax_mhz"] > free["fmax_mhz"], f"with a higher f_max: {free['fmax_mhz']} -> {clocked['fmax_mhz']} MHz")
expect(f"synthesised again with {knob}={last}" in open(f"{work}/choose_clock.err").read(),
       "choose says it synthesised the design again, and with what")
sys.exit(1 if failures else 0)
PY
echo PASS
