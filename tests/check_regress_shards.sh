#!/usr/bin/env bash
# A regression run as 3 shards under GNU parallel, joined by cdsim merge, must
# compare exactly what the whole run compares: the same triangles, fragments,
# setups, table writes, flags, and RTL cycles under back-pressure (each
# triangle's stalls are seeded by its number in the whole source), with 0
# mismatches. Usage: check_regress_shards.sh CDSIM WORKDIR
set -euo pipefail
cdsim=$1 work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work"
run=(regress --random 300 --seed 11 --backpressure 0.3 --design cd-linear,divide,affine-sub8,cd-dense2-linear --whole-unit)
"$cdsim" "${run[@]}" --json whole.json > whole.txt
parallel --halt now,fail=1 "$cdsim" "${run[@]}" --shard {}/3 --json shard{}.json '>' shard{}.txt ::: 1 2 3
"$cdsim" merge shard1.json shard2.json shard3.json --out merged.json > merged.txt
/usr/bin/python3 - <<'PY'
import json, sys
whole, merged = json.load(open("whole.json")), json.load(open("merged.json"))
shards = [json.load(open(f"shard{i}.json")) for i in (1, 2, 3)]
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
for key in ["triangles", "fragments", "mismatches", "hangs", "setups_compared", "table_writes_compared",
            "y_major_triangles", "flags", "source", "widths", "seed"]:
    expect(merged[key] == whole[key], f"merged {key} = the whole run's ({whole[key]})")
# Each shard is a stream of its own, from an idle unit: its clocks are its
# own, and the merge sums them. Overlap across a shard boundary is lost, so the
# sum is at least the whole run's.
for key in ["rtl_cycles", "model_cycles", "clocks", "model_clocks"]:
    expect(merged[key] == sum(s[key] for s in shards), f"merged {key} = the sum of the shards' ({merged[key]})")
expect(whole["model_cycles"] <= merged["model_cycles"], "shards lose only the overlap at their boundaries")
expect(all(0 < s["triangles"] < whole["triangles"] for s in shards), "each shard runs part of the triangles")
expect(whole["mismatches"] == 0 and whole["fragments"] > 10000, "the whole run compared its fragments exactly")
expect(whole["rtl_cycles"] > whole["model_cycles"], "back-pressure stalled the RTL")
for name, run in [("whole run", whole)] + [(f"shard {i}", s) for i, s in zip((1, 2, 3), shards)]:
    expect(run["clocks"] == run["model_clocks"] == run["rtl_cycles"],
           f"{name}: every clock counted, once: the records' cycles add up to the clocks "
           f"from the first accept to the last record ({run['clocks']})")
sys.exit(1 if failures else 0)
PY
# A shard missing is refused.
if "$cdsim" merge shard1.json shard3.json --out bad.json 2> missing.txt; then echo "FAIL: merge without shard 2"; exit 1; fi
grep -q "shard 2/3 missing" missing.txt && echo "ok   merge refuses a missing shard: $(cat missing.txt)"
