#!/usr/bin/env python3
"""The encodings of model/encodings.def are used by name (issue 38 item 4):
- the scan unit's state, front, fill and kind encodings are typed enums or
  localparams whose values are the CD_<GROUP>_<NAME> macros, and every code of
  those groups is named in rtl/cd_scan_unit.sv;
- neither the RTL nor the cover points compare a state, front, fill or kind
  variable with a number, or index the observation ports with one;
- every observation bit and field (OBS_* groups) is placed by name in the
  unit (CD_OBS_*), read by name in the bench (encoding::OBS_*), written by
  name in the vectors writer and read by name in the vectors testbench; the
  vectors-only EPS_CHECKED bit need not reach the unit or the bench;
- the cover file names every state, front and fill code it covers by macro.
Usage: check_encodings.py SOURCE_DIR
"""
import os
import re
import sys

source = sys.argv[1]
failures = []


def expect(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def text(path):
    return open(os.path.join(source, path), encoding="utf-8").read()


def without_comments(code):
    code = re.sub(r"//[^\n]*", "", code)
    return re.sub(r"/\*.*?\*/", "", code, flags=re.S)


codes = {}
for group, name, value in re.findall(r"^CDSIM_ENCODING\((\w+), (\w+), (\d+),", text("model/encodings.def"), re.M):
    codes.setdefault(group, []).append((name, int(value)))
expect({"KIND", "STATE", "FRONT", "FILL", "FLAG", "OBS_SETUP", "OBS_WRITE", "OBS_BOX", "OBS_LINES"} <= set(codes),
       "encodings.def has the kind, state, front, fill, flag and observation groups")

unit = without_comments(text("rtl/cd_scan_unit.sv"))
cover = without_comments(text("sim/cover/cd_scan_cover.sv"))
bench = without_comments(text("sim/bench.hpp"))
vectors = without_comments(text("sim/vectors.cpp"))
testbench = without_comments(text("tests/vectors/cd_scan_vectors_tb.sv"))

for group in ("STATE", "FRONT", "FILL", "KIND"):
    for name, _ in codes.get(group, []):
        if group == "KIND" and name == "CONSTANT_DEPTH":
            continue  # the unit tests the other kinds; constant depth is "none of them"
        expect(f"`CD_{group}_{name}" in unit, f"rtl/cd_scan_unit.sv names CD_{group}_{name}")
for enum in ("state_e", "front_e", "fill_e"):
    expect(re.search(r"typedef enum logic \[`CD_\w+_BITS-1:0\] \{[^}]*\} " + enum + ";", unit) is not None,
           f"rtl/cd_scan_unit.sv: {enum} is a typed enum of a CD_*_BITS width")

# A state, front, fill or kind variable compared with, or assigned, a number.
literal = re.compile(r"\b(state|front|fill|f_kind|kind)(_[dq]|_i)?\s*(==|!=|<=|=)\s*\d*'[dbh]\s*\d+")
rtl_files = [os.path.join("rtl", f) for f in sorted(os.listdir(os.path.join(source, "rtl"))) if f.endswith(".sv")]
for path in rtl_files + ["sim/cover/cd_scan_cover.sv"]:
    hits = literal.findall(without_comments(text(path)))
    expect(not hits, f"{path}: no state, front, fill or kind against a number ({len(hits)} found)")
expect(re.search(r"\.kind_i\s*\(\s*\d*'[dbh]", without_comments(text("rtl/adaptive_unit.sv"))) is None,
       "rtl/adaptive_unit.sv drives kind_i by name")
for group, state in (("STATE", "state_q"), ("FRONT", "front_q"), ("FILL", "fill_q")):
    for name, _ in codes.get(group, []):
        if group in ("FRONT", "FILL") and name == "IDLE":
            continue  # idle is the complement of the others
        expect(f"{state} == `CD_{group}_{name}" in cover, f"sim/cover: covers {state} == CD_{group}_{name}")
for path, code in (("rtl/cd_scan_unit.sv", unit), ("sim/cover/cd_scan_cover.sv", cover),
                   ("tests/vectors/cd_scan_vectors_tb.sv", testbench)):
    hits = re.findall(r"obs_(?:setup_bits|write_flags|setup_box|setup_lines)(?:_o)?\s*\[\s*\d", code)
    expect(not hits, f"{path}: no observation port indexed by a number ({len(hits)} found)")

for group in ("OBS_SETUP", "OBS_WRITE", "OBS_BOX", "OBS_LINES"):
    for name, _ in codes.get(group, []):
        vectors_only = group == "OBS_WRITE" and name == "EPS_CHECKED"
        if not vectors_only:
            expect(f"`CD_{group}_{name}" in unit, f"rtl/cd_scan_unit.sv places CD_{group}_{name}")
            expect(f"encoding::{group}_{name}" in bench, f"sim/bench.hpp reads encoding::{group}_{name}")
        expect(f"encoding::{group}_{name}" in vectors, f"sim/vectors.cpp writes encoding::{group}_{name}")
        if group in ("OBS_SETUP", "OBS_WRITE"):
            expect(f"`CD_{group}_{name}" in testbench, f"the vectors testbench reads CD_{group}_{name}")
# The bench and the vectors writer unpack no observation word by a bare shift or mask.
for path, code in (("sim/bench.hpp", bench), ("sim/vectors.cpp", vectors)):
    hits = re.findall(r"(?:bits|box|lines|flags|obs_\w+)\s*>>\s*\d+|<<\s*(?:48|32|16)\b", code)
    expect(not hits, f"{path}: no observation field at a numbered shift ({hits[:3]})")
# The testbench's words come from vectors.svh, not its own copy of the layouts.
expect(re.search(r"typedef\s+struct", testbench) is None, "the vectors testbench declares no word layout of its own")
expect("struct_typedef(kTriangle" in vectors, "sim/vectors.cpp writes the layouts into vectors.svh")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all encodings used by name")
