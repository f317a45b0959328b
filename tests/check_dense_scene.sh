#!/usr/bin/env bash
# The embedded dense scene (--scene dense) has what it is for: tens of
# thousands of triangles of a few pixels each, and `cdsim run` prints a cycle
# breakdown (setup-bound, fill-bound, walk, record) that adds up to each
# design's cycles, in its table and in its JSON, with 1 record clock a triangle.
# Usage: check_dense_scene.sh CDSIM WORKDIR
set -euo pipefail
cdsim=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
"$cdsim" run --scene dense --design cd-linear,divide --json "$work/run.json" > "$work/run.txt"
cat "$work/run.txt"
/usr/bin/python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
run = json.load(open(f"{work}/run.json"))
lines = open(f"{work}/run.txt").read().splitlines()
breakdown = lines[next(i for i, l in enumerate(lines) if l.startswith("cycles by phase")):]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
for d in run["designs"]:
    name, b = d["name"], d["cycle_breakdown"]
    per_triangle = d["pixels"] / d["triangles"]
    expect(d["triangles"] > 60000, f"{name}: {d['triangles']} triangles")
    expect(2 <= per_triangle <= 10, f"{name}: {per_triangle:.2f} pixels a triangle")
    expect(b["setup_bound"] + b["fill_bound"] + b["walk"] + b["record"] == d["cycles"],
           f"{name}: setup_bound + fill_bound + walk + record = cycles")
    expect(b["record"] == d["triangles"], f"{name}: one record clock a triangle")
    row = next(l for l in breakdown if l.startswith(name + " ")).split()
    expect([str(b[k]) for k in ("setup_bound", "fill_bound", "walk", "record")] == row[1:8:2],
           f"{name}: the breakdown table shows the JSON's figures")
expect(run["designs"][1]["cycle_breakdown"]["fill_bound"] == 0, "divide has no table fill")
sys.exit(1 if failures else 0)
PY
