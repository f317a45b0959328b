#!/usr/bin/env bash
# The component area model (rtl/area_model.json) against full synthesis: the
# designs that rtl_synth_design_blocks has synthesised into AREA_CACHE at
# narrow widths (cd-linear and divide; affine too with SCOPE long, which
# synthesises it: a minute or two of CI time) must be estimated within MAX_ERROR
# (a fraction, default 0.05) of their synthesised logic area and flip-flop table, with the same blocks, the same table bits and
# the estimate marked as such; every other design must be estimated (a
# positive area, marked as an estimate); and `sweep --area-model` must report
# the figures `cdsim area --model` gives.
# Usage: check_area_model.sh CDSIM WORKDIR "NARROW SETTINGS" AREA_CACHE [MAX_ERROR [SCOPE]]
set -euo pipefail
cdsim=$1 work=$2 narrow=$3 cache=$4 max_error=${5:-0.05} scope=${6:-ci}
rm -rf "$work" && mkdir -p "$work"
args=()
for s in $narrow; do args+=(--set "$s"); done
# Designs with RTL only: the others have no area to estimate.
# Not adaptive: the model does not cover its unit, so --model synthesises it
# (about 100 s at narrow widths; rtl_synth_design_blocks_long synthesises it).
designs=$("$cdsim" designs | grep -v 'no RTL yet' | awk '{print $1}' | grep -vx adaptive)
synthesised="cd-linear divide"  # as check_design_area.sh: no synthesis here
if [[ $scope == long ]]; then
  synthesised+=" affine"
else
  # Each estimate is an elaboration of about 5 s: in CI the synthesised designs
  # and one of each other family of blocks (fallback, Kim, subdivision, affine).
  designs=$(printf '%s\n' $designs | grep -xE 'cd-linear|divide|cd-persp-div|kim-pipe|quad-sub8|affine-sub8')
fi
for d in $synthesised; do
  "$cdsim" area --design "$d" "${args[@]}" --cache "$cache" --json "$work/synth_$d.json" > /dev/null
done
for d in $designs; do
  "$cdsim" area --model --design "$d" "${args[@]}" --cache "$cache" --json "$work/model_$d.json" > "$work/model_$d.txt"
done
scene=$(dirname "$0")/data/small_scene.tri
"$cdsim" sweep --scene "$scene" --design cd-linear,divide "${args[@]}" --area-model --out "$work/sweep" \
  > "$work/sweep.txt"

/usr/bin/python3 - "$work" "$max_error" $designs <<'PY'
import csv, json, sys
work, max_error, designs = sys.argv[1], float(sys.argv[2]), sys.argv[3:]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
import os
for d in designs:
    m = json.load(open(f"{work}/model_{d}.json"))
    expect("estimated by the component area model" in open(f"{work}/model_{d}.txt").read(),
           f"{d}: cdsim area --model says the figure is an estimate")
    if not os.path.exists(f"{work}/synth_{d}.json"):
        expect(m["estimated"] and m["logic_area_um2"] > 0 and m["blocks"], f"{d}: estimated, {m['logic_area_um2']:.0f} um^2")
        continue
    s = json.load(open(f"{work}/synth_{d}.json"))
    err = (m["logic_area_um2"] - s["logic_area_um2"]) / s["logic_area_um2"]
    expect(abs(err) <= max_error, f"{d}: model {m['logic_area_um2']:.0f} um^2 against synthesis "
                                  f"{s['logic_area_um2']:.0f} um^2 ({100 * err:+.2f}%, at most {100 * max_error:g}%)")
    expect([b["name"] for b in m["blocks"]] == [b["name"] for b in s["blocks"]], f"{d}: the same blocks")
    expect(m["sram_bits"] == s["sram_bits"], f"{d}: the same table bits")
    expect(m["estimated"] and not s["estimated"], f"{d}: the estimate says it is one")
    if s["flop_table_area_um2"] > 0:
        terr = (m["flop_table_area_um2"] - s["flop_table_area_um2"]) / s["flop_table_area_um2"]
        expect(abs(terr) <= max_error, f"{d}: flip-flop table within {100 * max_error:g}% ({100 * terr:+.2f}%)")
rows = list(csv.DictReader(open(f"{work}/sweep/sweep.csv")))
expect(len(rows) == 2, "sweep --area-model: two configurations")
for r in rows:
    m = json.load(open(f"{work}/model_{r['design']}.json"))
    expect(abs(float(r["total_area_um2"]) - m["total_area_um2"]) <= 1, f"sweep --area-model: {r['design']} as cdsim area --model")
sys.exit(1 if failures else 0)
PY
