#!/usr/bin/env bash
# scripts/survey-maps on a pak of one map (copied from the OpenArena pak):
# one row per design, each as `cdsim run --json` reports it; a second call
# resumes (runs nothing); a map the loader refuses is listed as refused.
# Usage: check_survey_maps.sh SURVEY CDSIM WORKDIR PAK
set -euo pipefail
survey=$1 cdsim=$2 work=$3 pak=$4
rm -rf "$work" && mkdir -p "$work"
[[ -f $pak ]] || { echo "no OpenArena pak $pak (scripts/setup installs openarena-081-maps)"; exit 1; }
/usr/bin/python3 - "$pak" "$work/one.pk3" "$work/bad.pk3" <<'PY'
import sys, zipfile
src, one, bad = sys.argv[1:]
z = zipfile.ZipFile(src)
name = "maps/oa_dm1.bsp"
with zipfile.ZipFile(one, "w") as o:
    o.writestr(name, z.read(name))
with zipfile.ZipFile(bad, "w") as o:
    o.writestr("maps/broken.bsp", b"IBSP" + b"\0" * 40)
PY
"$survey" --cdsim "$cdsim" --pak "$work/one.pk3" --spawns 1 --widths default "$work/out" > "$work/survey.txt"
"$survey" --cdsim "$cdsim" --pak "$work/one.pk3" --spawns 1 --widths default "$work/out" > "$work/again.txt" 2> "$work/again.err"
"$survey" --cdsim "$cdsim" --pak "$work/bad.pk3" --spawns 1 --widths default "$work/bad" > "$work/bad.txt"
"$cdsim" run --scene "$work/one.pk3:maps/oa_dm1.bsp" --spawn 0 --resolution 1920x1080 \
  --design cd-none,cd-linear,cd-dense2-linear,cd-persp,cd-linear-div,cd-persp-div,divide --json "$work/direct.json" > /dev/null
/usr/bin/python3 - "$work" <<'PY'
import csv, json, sys
work = sys.argv[1]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
rows = list(csv.DictReader(open(f"{work}/out/survey.csv")))
direct = {d["name"]: d for d in json.load(open(f"{work}/direct.json"))["designs"]}
expect(sorted(r["design"] for r in rows) == sorted(direct), f"one row per design ({len(rows)})")
for r in rows:
    d = direct[r["design"]]
    expect(int(r["pixels"]) == d["pixels"] and int(r["flagged_pixels"]) == d["flagged_pixels"]
           and abs(float(r["footprint_max"]) - d["error"]["footprint_max"]) <= 1e-12
           and abs(float(r["footprint_max_unflagged"]) - d["error_unflagged"]["footprint_max"]) <= 1e-12
           and r["fallback_pixels"] == str(d.get("fallback_pixels", "")),
           f"{r['design']}: the row is cdsim run's ({r['pixels']} pixels, fp_max {r['footprint_max']})")
expect("survey-maps: 1/1" not in open(f"{work}/again.err").read(), "a second call runs nothing")
expect("1 runs refused" in open(f"{work}/bad.txt").read(), "the broken map is listed as refused")
sys.exit(1 if failures else 0)
PY
