#!/usr/bin/env bash
# Usage: check_deep_json.sh CDSIM WORK_DIR QUAD_GLTF
# JSON inputs nested 20,000 levels deep (41 KB; they crashed cdsim with exit
# 139 through tinygltf's recursion) are made here rather than committed: the
# quad's glTF with such "extras", the same as a .glb, JSON scenes naming
# each, and the JSON files cdsim reads back (shard summaries, an area model).
# Every one must be refused with the depth named, not crash.
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
# Files cdsim writes and reads back: a regression shard's summary and a
# sweep shard's results (`cdsim merge`), an area model.
printf '{"kind": "cdsim regress", "shard": %s}\n' "$deep" > "$work/deep_shard.json"
"$here/expect_error.sh" "deep_shard.json:1: JSON nested deeper than 512 levels" \
  "$cdsim" merge "$work/deep_shard.json" --out "$work/merged.json" || status=1
mkdir -p "$work/deep_sweep" && printf '{"shard": %s}\n' "$deep" > "$work/deep_sweep/sweep.json"
"$here/expect_error.sh" "sweep.json:1: JSON nested deeper than 512 levels" \
  "$cdsim" merge "$work/deep_sweep" --out "$work/merged_sweep" || status=1
printf '{"flow": %s}\n' "$deep" > "$work/deep_model.json"
"$here/expect_error.sh" "deep_model.json:1: JSON nested deeper than 512 levels" \
  "$cdsim" area --model --model-file "$work/deep_model.json" --design cd-linear || status=1
exit $status
