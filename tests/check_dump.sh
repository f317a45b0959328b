#!/usr/bin/env bash
# run --dump: one row per fragment of the first design, and the error
# statistics recomputed from the rows (max(|u - exact u|, |v - exact v|))
# must be the ones run reports; the flags named in the rows must be those of
# the triangles run counts as flagged; the pixels with a datapath flag, and
# the error statistics over the others, recomputed from the rows, must be
# the ones run reports (issue 41).
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
# Flagged pixels and the error over the others, recomputed from the rows.
datapath = {"table_saturated", "output_saturated", "depth_range", "neighbour_dropped"}
marked = [bool(datapath & set(filter(None, r["flags"].split("|")))) for r in rows]
expect(sum(marked) == run["flagged_pixels"], f"flagged pixels: {sum(marked)} rows with a datapath flag, run says {run['flagged_pixels']}")
clean = [e for e, m in zip(errors, marked) if not m]
expect(0 < len(clean) < len(errors), f"both kinds of pixel ({len(errors) - len(clean)} flagged, {len(clean)} not)")
cmean, ctop = sum(clean) / len(clean), max(clean)
u = run["error_unflagged"]
expect(abs(cmean - u["mean"]) <= 1e-9 * max(1, cmean), f"mean error over unflagged rows {cmean:.6g} = run's {u['mean']:.6g}")
expect(abs(ctop - u["max"]) <= 1e-9 * max(1, ctop), f"max error over unflagged rows {ctop:.6g} = run's {u['max']:.6g}")
expect(u["max"] < run["error"]["max"], f"the flagged pixels hold the worst error ({u['max']:.4g} < {run['error']['max']:.4g})")
expect("errors over the pixels without a datapath flag" in open(f"{work}/run.txt").read(), "run prints the unflagged errors")
sys.exit(1 if failures else 0)
PY
