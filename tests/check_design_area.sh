#!/usr/bin/env bash
# Each design's unit holds only its own hardware: synthesises cd-linear,
# cd-persp, divide and affine at narrow widths (cdsim area, fresh cache) and
# checks the blocks each report lists. cd-linear has a table, a fill
# reciprocal and a correction adder and no per-pixel planes; cd-persp adds eps
# to the table word, a multiply to the fill and the weight to the correction
# adder, and nothing else; divide has no table and no
# correction adder, and a pixel reciprocal, multiply and plane accumulators;
# affine has no table and no reciprocal at all, and its own setup; quad-sub8
# has no table and no per-pixel multiply, and exact points (a reciprocal) and
# its subdivision datapath; adaptive is affine's blocks (its leaf unit) plus
# a split engine and the midpoints' reciprocal.
# cd-persp, affine, quad-sub8 and adaptive only with a fourth argument "long" (the long suite: CI's time).
# Usage: check_design_area.sh CDSIM WORKDIR "NARROW SETTINGS" [long]
set -euo pipefail
cdsim=$1 work=$2 narrow=$3 scope=${4:-ci}
rm -rf "$work" && mkdir -p "$work"
args=()
for s in $narrow; do args+=(--set "$s"); done
designs=(cd-linear divide)
[[ $scope == long ]] && designs+=(cd-persp affine quad-sub8 adaptive)
for d in "${designs[@]}"; do
  "$cdsim" area --design "$d" "${args[@]}" --cache "$work/cache" --json "$work/$d.json" >/dev/null
done
/usr/bin/python3 - "$work" <<'PY'
import json, os, sys
work = sys.argv[1]
failures = []
def load(design):
    r = json.load(open(f"{work}/{design}.json"))
    return r, {b["name"]: b["area_um2"] for b in r["blocks"]}
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
cd, cd_blocks = load("cd-linear")
dv, dv_blocks = load("divide")
long = os.path.exists(f"{work}/quad-sub8.json")
cp, cp_blocks = load("cd-persp") if long else ({}, {})
af, af_blocks = load("affine") if long else ({}, {})
qs, qs_blocks = load("quad-sub8") if long else ({}, {})
ad, ad_blocks = load("adaptive") if long else ({}, {})
for name, (r, b) in {"cd-linear": (cd, cd_blocks), "divide": (dv, dv_blocks),
                     **({"cd-persp": (cp, cp_blocks), "affine": (af, af_blocks), "quad-sub8": (qs, qs_blocks),
                         "adaptive": (ad, ad_blocks)} if long else {})}.items():
    total = sum(b.values())
    expect(abs(total - r["logic_area_um2"]) <= 1e-6 * total, f"{name}: blocks sum to the logic area ({total:.0f} um^2)")
expect(cd["sram_bits"] > 0, "cd-linear has a table")
expect(cd_blocks.get("correction adder", 0) > 0, "cd-linear has a correction adder")
expect(cd_blocks.get("reciprocal", 0) > 0, "cd-linear has the fill's reciprocal")
expect("plane accumulators" not in cd_blocks and "affine setup" not in cd_blocks, "cd-linear has no per-pixel planes")
expect(dv["sram_bits"] == 0 and dv["total_area_um2"] == dv["logic_area_um2"], "divide has no table")
expect("correction adder" not in dv_blocks, "divide has no correction adder")
expect(dv_blocks.get("reciprocal", 0) > 0 and dv_blocks.get("pixel multiply", 0) > 0, "divide has a pixel reciprocal and multiply")
expect(dv_blocks.get("plane accumulators", 0) > 0, "divide has plane accumulators")
expect(dv_blocks["setup engine"] < cd_blocks["setup engine"], "divide's setup engine has no slope divider, line range or fill")
# The widest multiply of each block (Yosys's $mul after wreduce): none in the
# walker, the contexts or the control; some in the setup engine, in divide's
# pixel multiply and in cd-linear's correction adder (its du/dx steps); no
# product wider than its operands' bits together (wreduce trims the rest).
def widest(r):
    return {b["name"]: b["widest_multiply"] for b in r["blocks"]}
cd_mul, dv_mul = widest(cd), widest(dv)
every = list(cd_mul.values()) + list(dv_mul.values())
expect(all(isinstance(m, dict) for m in every), f"every block states its widest multiply ({cd_mul}, {dv_mul})")
expect(all(cd_mul[b] == {} for b in ("column walker", "contexts", "control")),
       "cd-linear: no multiply in the walker, contexts or control")
expect(all(m["a_bits"] > 0 and m["b_bits"] > 0 and 0 < m["product_bits"] <= m["a_bits"] + m["b_bits"]
           for m in every if m), "each widest multiply: a product of at most a + b bits")
expect(bool(cd_mul["setup engine"]) and bool(dv_mul["setup engine"]), "both setup engines multiply")
expect(bool(dv_mul["pixel multiply"]) and bool(cd_mul["correction adder"]),
       "divide's pixel multiply and cd-linear's correction adder multiply")
# A quotient's multiply (cdsim::quotient) takes the numerator narrowed to the
# output format plus one integer bit and quotient_guard_bits, and R (recip_bits
# + 1 bits, unsigned: recip_bits + 2 signed), whatever the plane's width.
w = dv["widths"]
operand = w["out_int"] + w["out_frac"] + 1 + w["quotient_guard_bits"]
pm = dv_mul["pixel multiply"]
expect(pm and pm["a_bits"] == operand and pm["b_bits"] == w["recip_bits"] + 2,
       f"divide's pixel multiply is {operand} x {w['recip_bits'] + 2} bits ({pm})")
# Timing (OpenSTA on the mapped netlist): every block with flip-flops has a
# critical path, none without; the unit's is the longest of its blocks' (the
# scanline table's inputs aside, which count only for the unit), f_max is its
# inverse, and a 0.18 um unit runs between 10 and 400 MHz.
for name, r in {"cd-linear": cd, "divide": dv, **({"cd-persp": cp, "affine": af, "quad-sub8": qs, "adaptive": ad} if long else {})}.items():
    paths = {b["name"]: b["critical_path_ns"] for b in r["blocks"]}
    flops = {b["name"]: b["flops"] for b in r["blocks"]}
    expect(all((paths[b] is not None) == (flops[b] > 0) for b in paths),
           f"{name}: a critical path exactly for the blocks with flip-flops ({paths})")
    timed = [p for p in paths.values() if p is not None]
    expect(r["critical_path_ns"] >= max(timed) - 1e-9, f"{name}: the unit's path is at least each block's")
    expect(abs(r["fmax_mhz"] * r["critical_path_ns"] - 1000) < 1e-6, f"{name}: f_max = 1000 / critical path")
    expect(2.5 <= r["critical_path_ns"] <= 100, f"{name}: {r['critical_path_ns']:.2f} ns, {r['fmax_mhz']:.1f} MHz")
    expect(r["critical_path"]["from"] != "" and r["critical_path"]["to"] != "", f"{name}: the worst path's ends are named")
if long:
    expect(cp["sram_bits"] > cd["sram_bits"], f"cd-persp's table words hold eps ({cp['sram_bits']} bits against {cd['sram_bits']})")
    expect(cp_blocks["correction adder"] > cd_blocks["correction adder"], "cd-persp's correction adder has the weight's multiplies and ROM")
    expect(cp_blocks["setup engine"] > cd_blocks["setup engine"], "cd-persp's fill has the eps multiply")
    expect(set(cp_blocks) == set(cd_blocks), "cd-persp has cd-linear's blocks and no others")
    expect(af["sram_bits"] == 0, "affine has no table")
    expect(af_blocks.get("reciprocal", 0) == 0 and "pixel multiply" not in af_blocks, "affine has no reciprocal")
    expect(af_blocks.get("affine setup", 0) > 0 and af_blocks.get("plane accumulators", 0) > 0,
           "affine has its setup and accumulators")
    expect(qs["sram_bits"] == 0 and "correction adder" not in qs_blocks, "quad-sub8 has no table")
    expect(qs_blocks.get("exact points", 0) > 0 and qs_blocks.get("reciprocal", 0) > 0,
           "quad-sub8 has exact points and their reciprocal")
    expect(qs_blocks.get("subdivision datapath", 0) > 0 and "pixel multiply" not in qs_blocks,
           "quad-sub8 has its subdivision datapath and no per-pixel multiply")
    expect("plane accumulators" not in qs_blocks, "quad-sub8's point accumulators are in its exact points")
    expect(ad["sram_bits"] == 0, "adaptive has no table")
    expect(set(ad_blocks) == set(af_blocks) | {"split engine", "reciprocal"},
           f"adaptive has affine's blocks, a split engine and a reciprocal ({sorted(ad_blocks)})")
    # Its leaf unit has adapt_depth more subpixel bits and adapt_uv_extra more u, v bits than affine's.
    expect(ad_blocks["affine setup"] > af_blocks["affine setup"], "adaptive's leaf unit is wider than affine's")
sys.exit(1 if failures else 0)
PY
echo PASS
