#!/usr/bin/env bash
# The recovering flow on a real unit (cdsim area --flow recover, docs/area.md,
# "Area recovery"): DESIGN at the given widths synthesised by both flows into
# a fresh cache. The delay flow's own synthesis is the oracle: the recovering
# flow maps the same netlist at the delay corner in its own Yosys run, with
# the rounding shifters flattened (which only removes logic), so its
# all-delay logic must be no more than the delay flow's and its all-delay
# critical path (its target) within 5% of the delay flow's; the unit it
# chooses must meet that target (within 0.5%: docs/area.md), cost less logic than both, and no less
# than every module area-mapped; the blocks sum to the logic, are the delay
# flow's blocks, and hold no more flip-flops. Bad flows are refused.
# Usage: check_area_recover.sh CDSIM WORKDIR DESIGN "SETTINGS"
set -euo pipefail
cdsim=$1 work=$2 design=$3 settings=$4
rm -rf "$work" && mkdir -p "$work"
args=()
for s in $settings; do args+=(--set "$s"); done
for flow in delay recover; do
  "$cdsim" area --design "$design" "${args[@]}" --flow "$flow" --cache "$work/cache" --json "$work/$flow.json" \
    > "$work/$flow.txt"
done
grep -q "flow recover: [0-9]* of [0-9]* modules area-mapped" "$work/recover.txt"
/usr/bin/python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
d = json.load(open(f"{work}/delay.json"))
r = json.load(open(f"{work}/recover.json"))
rc = r["recovery"]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
expect(d["flow"] == "delay" and d["recovery"] is None, "the delay flow says so")
expect(r["flow"] == "recover", "the recovering flow says so")
expect(rc["delay_mapped_logic_um2"] <= d["logic_area_um2"],
       f"all delay-mapped, no more logic than the delay flow's ({rc['delay_mapped_logic_um2']:.0f} against "
       f"{d['logic_area_um2']:.0f} um^2)")
expect(abs(rc["target_ns"] - d["critical_path_ns"]) <= 0.05 * d["critical_path_ns"],
       f"the target, its all-delay critical path ({rc['target_ns']:.3f} ns), within 5% of the delay flow's "
       f"({d['critical_path_ns']:.3f})")
expect(r["critical_path_ns"] <= rc["target_ns"] * 1.005 + 0.001,
       f"the target is met within 0.5%: {r['critical_path_ns']:.3f} ns")
expect(r["logic_area_um2"] < rc["delay_mapped_logic_um2"],
       f"less logic than all delay-mapped ({r['logic_area_um2']:.0f} um^2)")
expect(r["logic_area_um2"] < d["logic_area_um2"],
       f"logic recovered: {r['logic_area_um2']:.0f} against {d['logic_area_um2']:.0f} um^2 "
       f"({100 * (r['logic_area_um2'] / d['logic_area_um2'] - 1):+.1f}%)")
expect(r["logic_area_um2"] >= rc["area_mapped_logic_um2"],
       f"no less than all area-mapped ({rc['area_mapped_logic_um2']:.0f} um^2)")
expect(0 < rc["area_mapped_modules"] < rc["modules"],
       f"{rc['area_mapped_modules']} of {rc['modules']} modules area-mapped, the critical path's not")
total = sum(b["area_um2"] for b in r["blocks"])
expect(abs(total - r["logic_area_um2"]) <= 1e-6 * total, "the blocks sum to the logic area")
expect([b["name"] for b in r["blocks"]] == [b["name"] for b in d["blocks"]], "the same blocks")
# The coarse passes merge and drop redundant flip-flops (divide's setup
# engine at narrow widths, M = 1: 5,054 against 5,087); they add none.
expect(all(b["flops"] <= c["flops"] for b, c in zip(r["blocks"], d["blocks"])),
       "no block has more flip-flops than in the delay flow")
sys.exit(1 if failures else 0)
PY
# Refusals: an unknown flow, and the component model (calibrated on the delay flow).
if "$cdsim" area --design "$design" --flow fast > "$work/bad.txt" 2>&1; then
  echo "FAIL --flow fast accepted"; exit 1
fi
grep -q "fast not in {delay,recover}" "$work/bad.txt" || { cat "$work/bad.txt"; exit 1; }
if "$cdsim" area --design "$design" --model --flow recover > "$work/bad.txt" 2>&1; then
  echo "FAIL --model --flow recover accepted"; exit 1
fi
grep -q "calibrated on the delay flow" "$work/bad.txt" || { cat "$work/bad.txt"; exit 1; }
echo "ok   bad flows refused"
