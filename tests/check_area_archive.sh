#!/usr/bin/env bash
# The committed component area model is the fit of the committed calibration
# archive: re-running its calibration command with --archive-only (no Yosys at
# all) must give the same coefficients and the same per-design errors, and must
# refuse a configuration the archive lacks.
# Usage: check_area_archive.sh CDSIM WORKDIR RTL_DIR
set -euo pipefail
cdsim=$1 work=$2 rtl=$3
rm -rf "$work" && mkdir -p "$work/cache"
# A model calibrated on other RTL sources cannot be refitted from its archive
# (every key names the RTL's hash): the test is skipped (ctest shows it, exit
# 77), naming the command that recalibrates; `cdsim area --model` warns too.
"$cdsim" area --model --design cd-linear > "$work/estimate.txt" 2>&1 || { cat "$work/estimate.txt"; echo "FAIL area --model"; exit 1; }
if grep -q "calibrated on other RTL sources" "$work/estimate.txt"; then
  echo "SKIP: rtl/area_model.json and its archive are of other RTL sources than rtl/ holds;"
  echo "      recalibrate: $(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["calibration"]["command"])' "$rtl/area_model.json")"
  exit 77
fi
command=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["calibration"]["command"])' \
  "$rtl/area_model.json")
read -r -a words <<< "$command"
[[ ${words[0]} == cdsim && ${words[1]} == area-model ]] || { echo "FAIL unexpected command: $command"; exit 1; }
"$cdsim" "${words[@]:1}" --archive-only --archive "$rtl/area_calibration.json" --cache "$work/cache" \
  --write "$work/model.json" > "$work/refit.txt"

# One more configuration than the archive holds must be refused, naming the archive.
configs=$(/usr/bin/python3 -c 'import json,sys; c=json.load(open(sys.argv[1]))["calibration"]["per_design"]; print(max(d["configs"] for d in c))' \
  "$rtl/area_model.json")
if "$cdsim" area-model --configs $((configs + 1)) --design cd-linear --archive-only \
     --archive "$rtl/area_calibration.json" --cache "$work/cache" --write "$work/more.json" \
     > "$work/more.txt" 2>&1; then
  echo "FAIL --archive-only accepted a configuration the archive lacks"; exit 1
fi
grep -q "are not in .*area_calibration.json" "$work/more.txt" || { echo "FAIL no message naming the archive"; cat "$work/more.txt"; exit 1; }

/usr/bin/python3 - "$rtl/area_model.json" "$work/model.json" <<'PY'
import json, math, sys
committed, refit = (json.load(open(p)) for p in sys.argv[1:])
failures = []
def expect(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond: failures.append(what)
expect(committed["rtl_hash"] == refit["rtl_hash"], "calibrated on the RTL in rtl/ (rtl_hash)")
expect(sorted(committed["coefficients"]) == sorted(refit["coefficients"]), "same module kinds")
for kind, c in committed["coefficients"].items():
    r = refit["coefficients"].get(kind, [])
    expect(len(r) == len(c) and all(math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9) for a, b in zip(c, r)),
           f"coefficients of {kind}")
for a, b in zip(committed["calibration"]["per_design"], refit["calibration"]["per_design"]):
    expect(a["design"] == b["design"] and a["configs"] == b["configs"]
           and math.isclose(a["max_abs_error"], b["max_abs_error"], rel_tol=1e-9, abs_tol=1e-12),
           f"{a['design']}: {a['configs']} configurations, max error {100 * a['max_abs_error']:.2f}%")
sys.exit(1 if failures else 0)
PY
