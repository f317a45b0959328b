#!/usr/bin/env bash
# cdsim vectors, replayed by the standalone SystemVerilog bench
# (tests/vectors/cd_scan_vectors_tb.sv, verilator --binary, no SystemC):
#  1. writes vectors of SOURCE (cdsim vectors' --scene or --random arguments)
#     with every design at narrow widths;
#  2. builds the bench and replays them, without and with back-pressure;
#  3. corrupts one word of each expected file in a copy (a fragment's u, a
#     table write's T.v, a setup's box, a record's cycles) and of the stimulus,
#     and requires the bench to fail, naming the triangle, block and field.
# Usage: check_vectors.sh CDSIM WORKDIR "SOURCE" TESTBENCH RTL_SOURCE...
set -euo pipefail
cdsim=$1 work=$2 source=$3 bench=$4
shift 4
rtl_sources=("$@")
rtl_dir=$(dirname "${rtl_sources[0]}")
rm -rf "$work" && mkdir -p "$work"
vec=$work/vectors

# shellcheck disable=SC2086  # SOURCE is words: --scene NAME, or --random N --seed S
"$cdsim" vectors --widths narrow $source --design mix --out "$vec"
for f in triangles.hex setups.hex table_writes.hex fragments.hex records.hex vectors.svh cd_widths.svh manifest.json; do
  [[ -s $vec/$f ]] || { echo "FAIL: $vec/$f is missing or empty"; exit 1; }
done

# Verilator's C++ at -O1: the bench runs a few million cycles, so a quicker
# compile beats a faster model here; the code run once (the __Slow files) at
# -O0, as the RTL cache builds it.
start=$SECONDS
verilator --binary -Wall -j "$(nproc)" -O3 -CFLAGS -O1 -MAKEFLAGS OPT_SLOW=-O0 --Mdir "$work/obj" \
  -I"$vec" -I"$rtl_dir" --top-module cd_scan_vectors_tb "$bench" "${rtl_sources[@]}" >"$work/build.log" 2>&1 ||
  { tail -40 "$work/build.log"; echo "FAIL: the bench does not build"; exit 1; }
echo "bench built in $((SECONDS - start)) s"
tb=$work/obj/Vcd_scan_vectors_tb

expect_pass() {  # label, plusargs...
  local label=$1; shift
  local out=$work/$label.log
  if ! "$tb" "$@" >"$out" 2>&1; then
    tail -30 "$out"; echo "FAIL: $label: the bench failed on the model's own vectors"; exit 1
  fi
  grep -q "vectors: PASS" "$out" || { cat "$out"; echo "FAIL: $label: no PASS line"; exit 1; }
  grep "fragments compared" "$out"
}
expect_pass clean +vectors="$vec"
expect_pass backpressure +vectors="$vec" +backpressure=300 +seed=7

# Each corruption must make the bench fail with a message that names it.
corrupt() {  # label, file, expected message (grep -E)
  local label=$1 file=$2 message=$3
  local copy=$work/$label
  # Hard links: the corrupted file is written anew (os.replace), the rest shared.
  rm -rf "$copy" && cp -rl "$vec" "$copy"
  /usr/bin/python3 - "$copy" "$file" "$label" <<'PY'
import json, os, sys
folder, name, label = sys.argv[1:4]
manifest = json.load(open(f"{folder}/manifest.json"))
lines = open(f"{folder}/{name}").read().splitlines()
if not lines:
    sys.exit(f"{name} is empty: nothing to corrupt")
def words(file):
    names = [f["name"] for f in manifest["files"][file]["fields"]]
    return [dict(zip(names, (int(x, 16) for x in l.split("_"))))
            for l in open(f"{folder}/{file}").read().splitlines()]
target, bit = {"fragment": ("u", 0), "write": ("t_v", 0), "setup": ("box", 0), "record": ("cycles", 0),
               "stimulus": ("x1", 6)}[label]
index = len(lines) // 20  # early: the bench stops at the first mismatch
if label == "record":  # the bench compares a record when its triangle leaves: the second triangle's
    index = 1
if label == "setup":  # a triangle that is not empty, whose box counts
    index = next(i for i, w in enumerate(words(name)) if not w["bits"] & 1)
if label == "stimulus":  # of the first 20 triangles (the replay stops soon after), the one with the
    records = words("records.hex")  # most fragments, one vertex moved 2^6 subpixels
    index = max(range(min(20, len(records))), key=lambda i: records[i]["fragments"])
fields = lines[index].split("_")
names = [f["name"] for f in manifest["files"][name]["fields"]]
i = names.index(target)
value = int(fields[i], 16) ^ (1 << bit)
fields[i] = format(value, "0%dx" % len(fields[i]))
lines[index] = "_".join(fields)
open(f"{folder}/{name}.new", "w").write("\n".join(lines) + "\n")
os.replace(f"{folder}/{name}.new", f"{folder}/{name}")
print(f"{label}: flipped bit {bit} of {target} in word {index} of {name}")
PY
  local out=$work/$label.log
  if "$tb" +vectors="$copy" +max_mismatches=1 >"$out" 2>&1; then
    tail -5 "$out"; echo "FAIL: $label: the bench passed corrupted vectors"; exit 1
  fi
  grep -Eq "$message" "$out" || { tail -20 "$out"; echo "FAIL: $label: no message matching '$message'"; exit 1; }
  grep -m1 -E "MISMATCH|HANG" "$out"
}
corrupt fragment fragments.hex "MISMATCH triangle [0-9]+ fragment #[0-9]+ pixel .*field u:"
corrupt write table_writes.hex "MISMATCH triangle [0-9]+ table write #[0-9]+: field T.v:"
corrupt setup setups.hex "MISMATCH triangle [0-9]+ setup engine: field box:"
corrupt record records.hex "MISMATCH triangle [0-9]+ record \\(0 stall cycles\\): field cycles:"
corrupt stimulus triangles.hex "MISMATCH triangle [0-9]+ "
echo PASS
