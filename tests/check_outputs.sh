#!/usr/bin/env bash
# Outputs never overwrite an input of the run, never name one file twice, and
# --trace never replaces a device or a pipe: each such command line is refused
# before any work with a message naming both, exit status 2, and every file
# (the scene, the pipe) is as it was.
# Usage: check_outputs.sh CDSIM SCENE.tri WORK
set -u
cdsim=$1 scene=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cp "$scene" "$work/scene.tri"
ln -s scene.tri "$work/link.tri"
mkfifo "$work/fifo"
failures=0

refused() {  # regex, args...
  local regex=$1 out status
  shift
  out=$(cd "$work" && "$cdsim" "$@" 2>&1)
  status=$?
  if [ "$status" -ne 2 ] || ! grep -Eq -- "$regex" <<<"$out"; then
    echo "FAIL: cdsim $* (exit $status, expected 2 and /$regex/):"; echo "$out"
    failures=$((failures + 1))
  else
    echo "ok: cdsim $*: $(grep -E -- "$regex" <<<"$out" | head -1)"
  fi
  cmp -s "$scene" "$work/scene.tri" || { echo "FAIL: cdsim $* changed the scene"; failures=$((failures + 1)); cp "$scene" "$work/scene.tri"; }
}

refused "--json scene.tri: is the input --scene scene.tri" run --scene scene.tri --json scene.tri
refused "--json ./link.tri: is the input --scene scene.tri" run --scene scene.tri --json ./link.tri
refused "--dump scene.tri: is the input --scene link.tri" run --scene link.tri --dump scene.tri
refused "--json r.json and --dump ./r.json: both name one file" run --scene scene.tri --json r.json --dump ./r.json
refused "--json scene.tri: is the input --scene scene.tri" regress --scene scene.tri --json scene.tri
refused "--trace link.tri: is the input --scene scene.tri" regress --scene scene.tri --trace link.tri
refused "--trace fifo: is a pipe" regress --random 5 --trace fifo
refused "--trace r.json and --json r.json: both name one file" regress --random 5 --trace r.json --json r.json
[ -p "$work/fifo" ] || { echo "FAIL: the pipe was replaced"; failures=$((failures + 1)); }
left=$(find "$work" -mindepth 1 ! -name scene.tri ! -name link.tri ! -name fifo)
[ -z "$left" ] || { echo "FAIL: files written:"; echo "$left"; failures=$((failures + 1)); }
[ "$failures" -eq 0 ] || { echo "FAIL: $failures cases"; exit 1; }
echo PASS
