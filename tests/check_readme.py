#!/usr/bin/env python3
"""The README's figures and lists against the tool and the tree (issue 38):
- every design `cdsim designs` lists is named in the Designs bullet, and the
  count of designs the RTL implements is the number it lists;
- the number of derived widths is the row count of `cdsim widths`' derived
  section;
- the default sweep's size is the one `cdsim sweep` states;
- the Layout table has a row for every top-level folder of the tree and no
  other, its docs/ row names every docs/*.md and its scripts/ row every
  script.
Usage: check_readme.py CDSIM SOURCE_DIR SMALL_SCENE WORKDIR
"""
import os
import re
import shutil
import subprocess
import sys

cdsim, source, small_scene, work = sys.argv[1:5]
readme = open(os.path.join(source, "README.md"), encoding="utf-8").read()
failures = []


def expect(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def run(*args):
    return subprocess.run([cdsim, *args], check=True, capture_output=True, text=True).stdout


WORDS = ["zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven",
         "twelve", "thirteen", "fourteen", "fifteen", "sixteen", "seventeen", "eighteen", "nineteen",
         "twenty"]

# ---- designs ---------------------------------------------------------------
designs = [line.split()[0] for line in run("designs").splitlines() if line.strip()]
expect(len(designs) >= 2, f"cdsim designs lists designs ({len(designs)})")
bullet = re.search(r"^- Designs \(`cdsim designs`.*?(?=^- )", readme, re.S | re.M)
expect(bullet is not None, "the README has a Designs bullet")
named = set(re.findall(r"`([a-z0-9-]+)`", bullet.group(0))) if bullet else set()
missing = [d for d in designs if d not in named]
expect(not missing, f"the Designs bullet names every design (missing: {missing})")
unknown = sorted(n for n in named if n not in designs and n != "cdsim")
expect(not unknown, f"the Designs bullet names no design cdsim lacks ({unknown})")
rtl = re.search(r"implements all (\w+) designs: (\w+)\s+in the scan unit", readme)
expect(rtl is not None, "the README states how many designs the RTL implements")
if rtl:
    # adaptive has a unit of its own (regress --design mix: the others in turn).
    expect(rtl.group(1) == WORDS[len(designs)] and rtl.group(2) == WORDS[len(designs) - 1] and "adaptive" in designs,
           f"the RTL implements all {rtl.group(1)} designs, {rtl.group(2)} in the scan unit "
           f"(cdsim designs: {len(designs)}, adaptive apart)")

# ---- derived widths --------------------------------------------------------
widths = run("widths").splitlines()
start = next(i for i, line in enumerate(widths) if line.startswith("derived (RTL)"))
rows = 0
for line in widths[start + 1:]:
    if not line.strip():
        break
    rows += 1
stated = re.search(r"every width the\s+hardware derives from them \((\d+),", readme)
expect(stated is not None, "the README states the number of derived widths")
if stated:
    expect(int(stated.group(1)) == rows, f"derived widths: README {stated.group(1)}, cdsim widths {rows}")

# ---- the default sweep -----------------------------------------------------
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
# One shard of many: the sweep states its size and runs one configuration.
out = run("sweep", "--scene", small_scene, "--out", os.path.join(work, "sweep"), "--shard", "1/100000")
total = re.search(r"of the (\d+) configurations", out)
expect(total is not None, "cdsim sweep states its size")
stated = re.search(r"default sweep\s+\((\d+) configurations", readme)
expect(stated is not None, "the README states the default sweep's size")
if total and stated:
    expect(stated.group(1) == total.group(1), f"default sweep: README {stated.group(1)}, cdsim {total.group(1)}")

# ---- layout ----------------------------------------------------------------
layout = re.search(r"^## Layout\n(.*?)(?=^## )", readme, re.S | re.M)
expect(layout is not None, "the README has a Layout section")
table = {}
for line in (layout.group(1) if layout else "").splitlines():
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if len(cells) == 2 and cells[0].endswith("/"):
        table[cells[0].rstrip("/")] = cells[1]
tracked = subprocess.run(["git", "-C", source, "ls-files"], check=True, capture_output=True,
                         text=True).stdout.splitlines()
folders = {p.split("/")[0] for p in tracked if "/" in p and not p.startswith(".")}
expect(set(table) == folders,
       f"the Layout table has a row for every top-level folder (missing: {sorted(folders - set(table))}, "
       f"not in the tree: {sorted(set(table) - folders)})")
docs = sorted(p[len("docs/"):-len(".md")] for p in tracked if re.fullmatch(r"docs/[^/]+\.md", p))
unnamed = [d for d in docs if d not in table.get("docs", "")]
expect(not unnamed, f"the docs/ row names every docs/*.md (missing: {unnamed})")
scripts = sorted(p[len("scripts/"):] for p in tracked
                 if re.fullmatch(r"scripts/[^/.]+", p) and os.access(os.path.join(source, p), os.X_OK))
unnamed = [s for s in scripts if f"`{s}`" not in table.get("scripts", "")]
expect(not unnamed, f"the scripts/ row names every script (missing: {unnamed})")

if failures:
    sys.exit(f"FAIL: {len(failures)} README checks")
print("PASS")
