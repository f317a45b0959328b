#!/usr/bin/env bash
# Usage: check_deep_json.sh CDSIM WORK_DIR QUAD_GLTF
# JSON inputs nested 20,000 levels deep (41 KB; they crashed cdsim with exit
# 139 through tinygltf's recursion) are made here rather than committed: the
# quad's glTF with such "extras", the same as a .glb, and JSON scenes naming
# each. Every one must be refused with the depth named, not crash.
set -u
cdsim=$1; work=$2; quad=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work" || exit 1
deep=$(printf '%*s' 20000 '' | tr ' ' '[')$(printf '%*s' 20000 '' | tr ' ' ']')
# The quad's object with "extras" first: its text after the opening brace.
{ printf '{"extras":%s,' "$deep"; tail -c +2 "$quad"; } > "$work/deep.gltf"
u32() { printf "\\x$(printf %02x $(($1 & 255)))\\x$(printf %02x $((($1 >> 8) & 255)))\\x$(printf %02x $((($1 >> 16) & 255)))\\x$(printf %02x $((($1 >> 24) & 255)))"; }
json_length=$(wc -c < "$work/deep.gltf")
padding=$(( (4 - json_length % 4) % 4 ))
json_length=$((json_length + padding))
{ printf 'glTF'; u32 2; u32 $((20 + json_length)); u32 "$json_length"; printf 'JSON'
  cat "$work/deep.gltf"; printf '%*s' "$padding" ''; } > "$work/deep.glb"
camera='"camera": {"eye": [0, 0, 1], "target": [0, 0, -3], "fov_y": 60}'
printf '{"mesh": "deep.gltf", %s}\n' "$camera" > "$work/deep_gltf_scene.json"
printf '{"mesh": "deep.glb", %s}\n' "$camera" > "$work/deep_glb_scene.json"
printf '{"mesh": "deep.gltf", "extras": %s, %s}\n' "$deep" "$camera" > "$work/deep_scene.json"
status=0
check() {  # REGEX SCENE [OPTIONS...]
  local regex=$1; shift
  "$here/expect_error.sh" "$regex" "$cdsim" run --design cd-linear --scene "$@" || status=1
}
check "deep.gltf:1: JSON nested deeper than 512 levels" "$work/deep.gltf" --camera 0,0,1,0,0,-3,0,1,0,60
check "deep.glb \(JSON chunk\):1: JSON nested deeper than 512 levels" "$work/deep.glb" --camera 0,0,1,0,0,-3,0,1,0,60
check "deep.gltf:1: JSON nested deeper than 512 levels" "$work/deep_gltf_scene.json"
check "deep.glb \(JSON chunk\):1: JSON nested deeper than 512 levels" "$work/deep_glb_scene.json"
check "deep_scene.json:1: JSON nested deeper than 512 levels" "$work/deep_scene.json"
exit $status
