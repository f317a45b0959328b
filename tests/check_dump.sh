#!/usr/bin/env bash
# run --dump: one row per fragment of the first design, and the error
# statistics recomputed from the rows (max(|u - exact u|, |v - exact v|))
# must be the ones run reports; the flags named in the rows must be those of
# the triangles run counts as flagged.
# Usage: check_dump.sh CDSIM WORKDIR SCENE
set -euo pipefail
cdsim=$1 work=$2 scene=$3
rm -rf "$work" && mkdir -p "$work"
"$cdsim" run --scene "$scene" --design cd-linear,divide --set out_int=8 --dump "$work/dump.csv" \
  --json "$work/run.json" > "$work/run.txt"
/usr/bin/python3 - "$work" <<'PY'
import csv, json, sys
work = sys.argv[1]
rows = list(csv.DictReader(open(f"{work}/dump.csv")))
run = json.load(open(f"{work}/run.json"))["designs"][0]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
expect(run["name"] == "cd-linear", "the first design is dumped")
expect(len(rows) == run["pixels"], f"one row per fragment ({len(rows)} rows, {run['pixels']} pixels)")
errors = [max(abs(float(r["u"]) - float(r["exact_u"])), abs(float(r["v"]) - float(r["exact_v"]))) for r in rows]
mean, top = sum(errors) / len(errors), max(errors)
expect(abs(mean - run["error"]["mean"]) <= 1e-9 * max(1, mean), f"mean error from the rows {mean:.6g} = run's {run['error']['mean']:.6g}")
expect(abs(top - run["error"]["max"]) <= 1e-9 * max(1, top), f"max error from the rows {top:.6g} = run's {run['error']['max']:.6g}")
flagged = {}
for r in rows:
    for name in filter(None, r["flags"].split("|")):
        flagged.setdefault(name, set()).add(r["triangle"])
for name, count in run["flags"].items():
    if name in ("banded", "table_saturated", "depth_range"): continue  # not always on a fragment
    n = len(flagged.get(name, ()))
    # An output saturates on a fragment, so its triangles are exactly those rows name.
    expect(n == count if name == "output_saturated" else n <= count, f"{name}: rows of {n} triangles, run counts {count}")
expect(sum(len(v) for v in flagged.values()) > 0, "some fragments carry flags at out_int=8")
sys.exit(1 if failures else 0)
PY
