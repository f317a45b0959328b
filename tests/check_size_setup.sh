#!/usr/bin/env bash
# `cdsim size` prices the setup engine at the widths it finds: each row of its
# table (setup_multipliers M: cycles) must be what `cdsim run` counts at those
# widths with --set setup_multipliers=M, and its slowdown the ratio to M = 0.
# Usage: check_size_setup.sh CDSIM SCENE WORKDIR
set -euo pipefail
cdsim=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
"$cdsim" size --scene "$scene" --design cd-linear --max-error 0.5 --metric footprint > "$work/size.txt"
widths=$(sed -n 's/^result ([0-9]* model runs): //p' "$work/size.txt")
[[ -n $widths ]] || { echo "FAIL no result line"; cat "$work/size.txt"; exit 1; }
args=()
for s in $widths; do [[ $s == setup_multipliers=* ]] || args+=(--set "$s"); done
for m in 0 1 2 4 8; do
  "$cdsim" run --scene "$scene" --design cd-linear "${args[@]}" --set setup_multipliers=$m \
    --json "$work/run_$m.json" > /dev/null
done
/usr/bin/python3 - "$work" <<'PY'
import json, re, sys
work = sys.argv[1]
text = open(f"{work}/size.txt").read()
rows = {}
for line in text.split("setup engine at these widths", 1)[1].splitlines()[2:]:
    m = re.match(r"\s*(\d+)(?: \(one per product\))?\s+(\d+)\s+(\d+)\s+([\d.]+)\s+([\d.]+)", line)
    if m: rows[int(m.group(1))] = (int(m.group(3)), float(m.group(5)))
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
expect(sorted(rows) == [0, 1, 2, 4, 8], f"a row for M = 0, 1, 2, 4, 8 ({sorted(rows)})")
runs = {m: json.load(open(f"{work}/run_{m}.json"))["designs"][0]["cycles"] for m in [0, 1, 2, 4, 8]}
for m, (cycles, slowdown) in rows.items():
    expect(cycles == runs[m], f"M = {m}: size's {cycles} cycles are run's {runs[m]}")
    expect(abs(slowdown - runs[m] / runs[0]) < 1e-4, f"M = {m}: slowdown {slowdown} = {runs[m] / runs[0]:.4f}")
expect(all(runs[m] > runs[0] for m in [1, 2, 4, 8]), "a shared engine takes more cycles than the parallel one")
sys.exit(1 if failures else 0)
PY
