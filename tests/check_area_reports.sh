#!/usr/bin/env bash
# Area where users read it: `run --area`, `sweep --area` and `choose`.
# Each figure must be the one `cdsim area` gives for the same design and
# widths (the synthesis cache makes that check free), every design `choose`
# says meets the target must meet it when `cdsim run` measures it at the
# widths it printed, the ranking must be ordered by total area, and the
# winner must have passed its RTL check.
# Usage: check_area_reports.sh CDSIM WORKDIR "NARROW SETTINGS" [AREA_CACHE]
# AREA_CACHE: a synthesis cache to share (rtl_synth_design_blocks fills one
# with cd-linear and divide at the same narrow widths, so run and sweep cost
# no synthesis here; choose synthesises the widths it sizes).
set -euo pipefail
cdsim=$1 work=$2 narrow=$3 shared=${4:-}
rm -rf "$work" && mkdir -p "$work/cache/cdsim"
export XDG_CACHE_HOME=$work/cache  # run and sweep synthesise into the default cache
if [[ -n $shared ]]; then
  mkdir -p "$shared" && ln -s "$(realpath "$shared")" "$work/cache/cdsim/area"
fi
args=()
for s in $narrow; do args+=(--set "$s"); done
scene=$(dirname "$0")/data/small_scene.tri

"$cdsim" run --scene "$scene" --design cd-linear,divide "${args[@]}" --area --json "$work/run.json" > "$work/run.txt"
for d in cd-linear divide; do
  "$cdsim" area --design "$d" "${args[@]}" --json "$work/area_$d.json" > /dev/null
done
"$cdsim" sweep --scene "$scene" --design cd-linear,divide "${args[@]}" --area \
  --out "$work/sweep" > "$work/sweep.txt"
"$(dirname "$0")/../scripts/plot" "$work/sweep" > "$work/plot.txt"
"$cdsim" choose "$scene" --design affine,divide "${args[@]}" --metric footprint --max-error 100 \
  --verify-random 50 --json "$work/choose.json" > "$work/choose.txt"
# Two scenes of different viewports: the winner's RTL check runs both in one
# stream (a second SystemC bench in one process cannot be elaborated). With
# the winner's widths all set: its setup engine and table stay, and the second
# scene (one triangle of constant depth) needs no bit more, so sizing ends on
# the same widths and their synthesis is the cached one (no rate target: one
# triangle of about 1,000 pixels with its setup on one multiplier is below 0.9 px/clk).
winner=$(/usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["ranking"][0]["design"])' \
  "$work/choose.json")
mapfile -t winner_widths < <(/usr/bin/python3 -c 'import json, sys
for k, v in json.load(open(sys.argv[1]))["ranking"][0]["widths"].items(): print(f"--set\n{k}={v}")' "$work/choose.json")
syntheses() { find -L "$work/cache/cdsim/area" -name result.json | wc -l; }
before=$(syntheses)
"$cdsim" choose "$scene" "$(dirname "$0")/data/good.tri" --design "$winner" "${winner_widths[@]}" --metric footprint \
  --max-error 100 --min-rate 0 --verify-random 20 --json "$work/choose2.json" > "$work/choose2.txt"
echo "$before $(syntheses)" > "$work/choose2_syntheses.txt"
# The rate and clock targets. No design reaches 5 px/clk: both are refused,
# and neither is synthesised (an empty cache stays empty). A clock between the
# two designs' f_max refuses the slower one (its synthesis is cached), with
# --pipeline-steps 0: no step of pipelining, each a synthesis more (the long
# tests rtl_correction_timing and rtl_setup_register_timing take them).
"$cdsim" choose "$scene" --design affine,divide "${args[@]}" --metric footprint --max-error 100 --min-rate 5 \
  --no-verify --area-cache "$work/empty_cache" --json "$work/choose_rate.json" > "$work/choose_rate.txt"
clock=$(/usr/bin/python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))["ranking"]
print(round(sum(x["fmax_mhz"] for x in r) / len(r), 2))' "$work/choose.json")
"$cdsim" choose "$scene" --design affine,divide "${args[@]}" --metric footprint --max-error 100 \
  --clock-mhz "$clock" --pipeline-steps 0 --no-verify --area-cache "$work/cache/cdsim/area" \
  --json "$work/choose_clock.json" > "$work/choose_clock.txt" 2> "$work/choose_clock.err"

/usr/bin/python3 - "$work" "$cdsim" "$scene" <<'PY'
import csv, json, subprocess, sys
work, cdsim, scene = sys.argv[1:4]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
def close(a, b):
    return abs(a - b) <= 1e-6 * max(1.0, abs(b))
def close_csv(a, b):  # sweep.csv prints areas to 0.1 um^2
    return abs(a - b) <= 0.05 + 1e-6 * abs(b)
keys = ["logic_area_um2", "sram_bits", "sram_area_um2", "total_area_um2"]

run = json.load(open(f"{work}/run.json"))
for row in run["designs"]:
    d = row["name"]
    area = json.load(open(f"{work}/area_{d}.json"))
    expect(set(area) <= set(row["area"]), f"run --json: {d}'s 'area' holds every key of cdsim area --json")
    expect(all(close(row["area"][k], area[k]) for k in keys), f"run --area: {d} as cdsim area reports it")
    # The rates: f_max from cdsim area's timing, px/clk from the run itself.
    expect(area["fmax_mhz"] > 0 and close(area["fmax_mhz"], 1000 / area["critical_path_ns"]),
           f"cdsim area: {d}'s f_max is 1000 / its critical path ({area['fmax_mhz']:.1f} MHz)")
    # The critical block: the one whose worst path is the unit's, or the table's inputs.
    paths = {b["name"]: b["critical_path_ns"] for b in area["blocks"] if b["critical_path_ns"] is not None}
    if (area["table_critical_path_ns"] or 0) > max(paths.values()):
        paths["scanline table"] = area["table_critical_path_ns"]
    worst = max(paths, key=paths.get)
    expect(area["critical_block"] == worst and close(paths[worst], area["critical_path_ns"]),
           f"cdsim area: {d}'s critical block is {worst}, whose path is the unit's ({area['critical_block']})")
    expect(close(row["area"]["px_per_clk"], row["pixels"] / row["cycles"]),
           f"run --area: {d}'s px/clk is its pixels over its cycles")
    expect(close(row["area"]["mpix_per_s"], row["pixels"] / row["cycles"] * area["fmax_mhz"]),
           f"run --area: {d}'s Mpx/s is px/clk x f_max ({row['area']['mpix_per_s']:.2f})")
    expect(close(row["area"]["um2_per_mpix_per_s"], area["total_area_um2"] / row["area"]["mpix_per_s"]),
           f"run --area: {d}'s area per Mpx/s")
text = open(f"{work}/run.txt").read()
expect(f"{area['total_area_um2']:.0f}" in text, "run --area prints the total in its table")
expect(f"{area['fmax_mhz']:.1f}" in text and "Mpx/s" in text, "run --area prints f_max and Mpx/s in its table")

rows = list(csv.DictReader(open(f"{work}/sweep/sweep.csv")))
expect(len(rows) == 2, "sweep: two configurations")
for r in rows:
    area = json.load(open(f"{work}/area_{r['design']}.json"))
    expect(all(close_csv(float(r[k]), area[k]) for k in keys), f"sweep --area: {r['design']} as cdsim area reports it")
    expect(close_csv(float(r["total_area_um2"]), float(r["logic_area_um2"]) + float(r["sram_area_um2"])),
           "sweep: total = logic + SRAM")
    expect(abs(float(r["fmax_mhz"]) - area["fmax_mhz"]) <= 0.005, f"sweep --area: {r['design']}'s f_max as cdsim area's")
    expect(abs(float(r["mpix_per_s"]) - float(r["pixels_per_clock"]) * area["fmax_mhz"]) <= 0.01,
           f"sweep --area: {r['design']}'s Mpx/s = px/clk x f_max")
sweep = json.load(open(f"{work}/sweep/sweep.json"))
expect(all("area" in r for r in sweep["rows"]), "sweep.json: every row has its area")

import os
expect(os.path.getsize(f"{work}/sweep/area_vs_error.png") > 10000, "plot: area_vs_error.png drawn")
expect("wrote" in open(f"{work}/plot.txt").read() and "area plots skipped" not in open(f"{work}/plot.txt").read(),
       "plot: the sweep's area is used")
header = open(f"{work}/sweep/equal_error.csv").readline().strip().split(",")
expect("total_area_um2" in header and "area_ratio" in header, "equal_error.csv has area columns")

choose = json.load(open(f"{work}/choose.json"))
ranking = choose["ranking"]
expect(len(ranking) == 2, "choose: both designs ranked")
met = [r for r in ranking if r["meets"]]
expect(len(met) == 2, "choose: both meet a footprint error of 100")
areas = [r["total_area_um2"] for r in met]
expect(areas == sorted(areas), f"choose: ranked by total area {areas}")
for r in met:
    for key in ["design", "meets", "total_area_um2", "cycles", "error", "widths", "rtl_verified"]:
        expect(key in r, f"choose: {r['design']} has '{key}'")
    sets = []
    for name, value in r["widths"].items():
        sets += ["--set", f"{name}={value}"]
    out = subprocess.run([cdsim, "run", "--scene", scene, "--design", r["design"], *sets,
                          "--json", f"{work}/check_{r['design']}.json"], capture_output=True, text=True)
    expect(out.returncode == 0, f"choose: cdsim run at {r['design']}'s widths ({out.stderr.strip()})")
    measured = json.load(open(f"{work}/check_{r['design']}.json"))["designs"][0]
    expect(measured["name"] == r["design"], f"choose: run measured {r['design']}")
    expect(close(measured["error"]["footprint_max"], r["error"]), f"choose: {r['design']}'s error is what run measures")
    expect(measured["error"]["footprint_max"] <= 100, f"choose: {r['design']} meets the target when run measures it")
    expect(measured["cycles"] == r["cycles"], f"choose: {r['design']}'s cycles are what run counts")
    out = subprocess.run([cdsim, "area", "--design", r["design"], *sets, "--cache", f"{work}/cache/cdsim/area",
                          "--json", f"{work}/check_area_{r['design']}.json"], capture_output=True, text=True)
    expect(out.returncode == 0, f"choose: cdsim area at {r['design']}'s widths")
    area = json.load(open(f"{work}/check_area_{r['design']}.json"))
    expect(close(area["total_area_um2"], r["total_area_um2"]), f"choose: {r['design']}'s area is what cdsim area synthesises")
    expect(close(r["fmax_mhz"], area["fmax_mhz"]) and close(r["px_per_clk"], r["pixels"] / r["cycles"])
           and close(r["mpix_per_s"], r["px_per_clk"] * r["fmax_mhz"]),
           f"choose: {r['design']}'s f_max is cdsim area's, its Mpx/s px/clk x f_max ({r['mpix_per_s']:.2f})")
expect(ranking[0]["rtl_verified"] is True, "choose: the winner passed its RTL check")
expect("winner: " + ranking[0]["design"] in open(f"{work}/choose.txt").read(), "choose prints the winner")
two = json.load(open(f"{work}/choose2.json"))
expect(len(two["scenes"]) == 2 and two["ranking"][0]["rtl_verified"] is True,
       "choose on two scenes: the winner passed its RTL check")
text = open(f"{work}/choose2.txt").read()
expect("source: scene" in text and "source: then scene" in text and "0 mismatches" in text,
       "choose on two scenes: one RTL run holds both scenes")
before, after = open(f"{work}/choose2_syntheses.txt").read().split()
expect(two["ranking"][0]["widths"] == ranking[0]["widths"] and before == after,
       "choose on two scenes: an easier scene more leaves the widths, whose synthesis is cached")

import pathlib
rate = json.load(open(f"{work}/choose_rate.json"))
expect(rate["target"]["min_rate"] == 5, "choose --min-rate: the target is in the JSON")
for r in rate["ranking"]:
    expect(r["meets_error"] and r["meets_rate"] is False and r["meets"] is False,
           f"choose --min-rate 5: {r['design']} meets the error but is refused for its rate")
    expect(close(r["min_px_per_clk"], r["pixels"] / r["cycles"]) and r["min_px_per_clk"] < 5,
           f"choose --min-rate 5: {r['design']} listed with the rate it reaches ({r['min_px_per_clk']:.3f} px/clk)")
    expect(r["total_area_um2"] is None, f"choose --min-rate 5: {r['design']} not synthesised")
empty = pathlib.Path(f"{work}/empty_cache")
expect(not empty.exists() or not any(empty.rglob("result.json")), "choose --min-rate 5: no synthesis run")
text = open(f"{work}/choose_rate.txt").read()
expect("too slow:" in text and "no design with RTL meets the targets" in text,
       "choose --min-rate 5: the table says why, and that nothing wins")

clocked = json.load(open(f"{work}/choose_clock.json"))
target = clocked["target"]["clock_mhz"]
expect(clocked["target"]["pipeline_steps"] == 0 and "synthesised again" not in open(f"{work}/choose_clock.err").read(),
       "choose --pipeline-steps 0: no design synthesised again")
by_name = {r["design"]: r for r in clocked["ranking"]}
fast = max(ranking, key=lambda r: r["fmax_mhz"])["design"]
slow = min(ranking, key=lambda r: r["fmax_mhz"])["design"]
expect(fast != slow and by_name[slow]["fmax_mhz"] < target < by_name[fast]["fmax_mhz"],
       f"choose --clock-mhz {target:.1f}: between the two designs' f_max")
expect(by_name[slow]["meets_clock"] is False and by_name[slow]["meets"] is False and by_name[slow]["meets_rate"],
       f"choose --clock-mhz: {slow} refused for its clock ({by_name[slow]['fmax_mhz']:.1f} MHz)")
expect(by_name[fast]["meets_clock"] is True and clocked["ranking"][0]["design"] == fast,
       f"choose --clock-mhz: {fast} meets the clock and wins")
text = open(f"{work}/choose_clock.txt").read()
expect(f"winner: {fast}" in text and "too slow: f_max" in text
       and f"(the {by_name[slow]['area']['critical_block']}'s " in text,
       "choose --clock-mhz: the table says why, and which block sets the clock")
sys.exit(1 if failures else 0)
PY
echo PASS
