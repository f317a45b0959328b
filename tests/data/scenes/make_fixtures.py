#!/usr/bin/env python3
"""Writes the small scene fixtures of tests/loaders_test.cpp into this directory.

Run it again after changing it; the outputs are committed so that the tests
need nothing but the repository. Deterministic: same bytes every run.
"""
import base64
import json
import math
import os
import struct
import zipfile
import zlib


def png(w, h):
    raw = b''.join(b'\x00' + bytes([(x ^ y) & 255 for x in range(w) for _ in range(3)]) for y in range(h))

    def chunk(t, d):
        return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0)) +
            chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def write(name, data):
    with open(name, 'wb') as f:
        f.write(data.encode() if isinstance(data, str) else data)


# --- OBJ + MTL: a cube; four faces use a 64x32 texture, two a material without one.
write('checker_64x32.png', png(64, 32))
write('cube.mtl', """# Two materials: one with a texture whose header gives 64x32, one without.
newmtl checker
Kd 1 1 1
map_Kd checker_64x32.png

newmtl plain
Kd 0.5 0.5 0.5
""")


def corner(x, y, z):  # OBJ vertex number of the cube corner (x, y, z) in {0, 1}^3
    return 1 + 4 * x + 2 * y + z


obj = ["# Unit cube, quads (fanned into triangles by the loader).", "mtllib cube.mtl"]
obj += ["v %g %g %g" % (x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
obj += ["vt 0 0", "vt 2 0", "vt 2 2", "vt 0 2"]
faces = [
    ("checker", [corner(0, 0, 1), corner(1, 0, 1), corner(1, 1, 1), corner(0, 1, 1)]),
    ("checker", [corner(1, 0, 0), corner(0, 0, 0), corner(0, 1, 0), corner(1, 1, 0)]),
    ("checker", [corner(1, 0, 1), corner(1, 0, 0), corner(1, 1, 0), corner(1, 1, 1)]),
    ("checker", [corner(0, 0, 0), corner(0, 0, 1), corner(0, 1, 1), corner(0, 1, 0)]),
    ("plain", [corner(0, 1, 1), corner(1, 1, 1), corner(1, 1, 0), corner(0, 1, 0)]),
    ("plain", [corner(0, 0, 0), corner(1, 0, 0), corner(1, 0, 1), corner(0, 0, 1)]),
]
current = None
for material, face in faces:
    if material != current:
        obj.append("usemtl " + material)
        current = material
    obj.append("f " + " ".join("%d/%d" % (v, k + 1) for k, v in enumerate(face)))
write('cube.obj', "\n".join(obj) + "\n")

# --- glTF: one quad, node translated to z = -3, base colour texture.
tiny_png = png(16, 8)
positions = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
texcoords = [(0, 1), (1, 1), (1, 0), (0, 0)]
indices = [0, 1, 2, 0, 2, 3]
buffer = (b''.join(struct.pack('<3f', *p) for p in positions) +
          b''.join(struct.pack('<2f', *t) for t in texcoords) + struct.pack('<6H', *indices) + b'\0\0')


def gltf(image):
    return {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "translation": [0, 0, -3]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                    "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "textures": [{"source": 0}],
        "images": [image],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 32},
            {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
        "buffers": [{"byteLength": len(buffer),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()}],
    }


write('quad.gltf', json.dumps(gltf({"uri": "checker_64x32.png"}), indent=1) + "\n")
binary = buffer + tiny_png
binary += b'\0' * (-len(binary) % 4)
g = gltf({"bufferView": 3, "mimeType": "image/png"})
g["bufferViews"].append({"buffer": 0, "byteOffset": len(buffer), "byteLength": len(tiny_png)})
g["buffers"] = [{"byteLength": len(binary)}]
text = json.dumps(g).encode()
text += b' ' * (-len(text) % 4)
write('quad.glb', b'glTF' + struct.pack('<II', 2, 12 + 8 + len(text) + 8 + len(binary)) +
      struct.pack('<I', len(text)) + b'JSON' + text + struct.pack('<I', len(binary)) + b'BIN\0' + binary)

# --- JSON scenes.
write('cube_scene.json', json.dumps({
    "mesh": "cube.obj",
    "camera": {"eye": [3, 2, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 50},
    "resolution": [640, 360], "texture_size": [128, 128]}, indent=1) + "\n")
write('quad_scene.json', json.dumps({
    "mesh": "quad.glb",
    "camera": {"eye": [0.5, 0.3, 0], "target": [0, 0, -3], "fov_y": 60, "near": 0.1},
    "resolution": [320, 240]}, indent=1) + "\n")

# --- Quake 3 BSP (IBSP 46): a wall polygon, a 3x3 patch, a one-triangle mesh,
# a nodraw polygon and a billboard; two spawn points. Layout documented in
# tests/loaders_test.cpp, which corrupts it field by field.
entities = (b'{\n"classname" "worldspawn"\n}\n'
            b'{\n"classname" "info_player_deathmatch"\n"origin" "0 -200 0"\n"angle" "90"\n}\n'
            b'{\n"classname" "info_player_start"\n"origin" "64 -200 16"\n"angles" "10 45 0"\n}\n\0')
shaders = [("textures/test/wall", 0), ("textures/test/nodraw", 0x80), ("textures/test/missing", 0)]
vertices = [(-64, 0, 0, 0, 1), (64, 0, 0, 2, 1), (64, 0, 128, 2, -1), (-64, 0, 128, 0, -1)]
for j in range(3):          # patch control points: an arch bulging towards -y
    for i in range(3):
        vertices.append((-64 + 64 * i, -32 * (i == 1) - 16 * (j == 1), 128 + 32 * j, i * 0.5, j * 0.5))
vertices += [(0, -50, 0, 0, 0), (32, -50, 0, 1, 0), (0, -50, 32, 0, 1)]
meshverts = [0, 1, 2, 0, 2, 3, 0, 1, 2]
# texture, effect, type, vertex, n_vertexes, meshvert, n_meshverts, lm_index, lm_start[2], lm_size[2],
# lm_origin[3], lm_vecs[6], normal[3], size[2]
faces = [(0, 1, 0, 4, 0, 6, 0, 0), (2, 2, 4, 9, 0, 0, 3, 3), (0, 3, 13, 3, 6, 3, 0, 0),
         (1, 1, 0, 4, 0, 6, 0, 0), (0, 4, 0, 1, 0, 0, 0, 0)]
lumps = [b''] * 17
lumps[0] = entities
lumps[1] = b''.join(n.encode().ljust(64, b'\0') + struct.pack('<ii', f, 1) for n, f in shaders)
lumps[10] = b''.join(struct.pack('<3f2f2f3f4B', x, y, z, s, t, 0, 0, 0, -1, 0, 255, 255, 255, 255)
                     for x, y, z, s, t in vertices)
lumps[11] = struct.pack('<%di' % len(meshverts), *meshverts)
lumps[13] = b''.join(struct.pack('<iiiiiiii', tex, -1, typ, v, nv, m, nm, -1) + struct.pack('<4i', 0, 0, 0, 0) +
                     struct.pack('<12f', *([0.0] * 12)) + struct.pack('<2i', w, h)
                     for tex, typ, v, nv, m, nm, w, h in faces)
header = b'IBSP' + struct.pack('<i', 46)
offset = 8 + 17 * 8
body = b''
for lump in lumps:
    header += struct.pack('<ii', offset + len(body), len(lump))
    body += lump + b'\0' * (-len(lump) % 4)
bsp = header + body
write('tiny.bsp', bsp)
with zipfile.ZipFile('tiny.pk3', 'w', zipfile.ZIP_DEFLATED) as z:
    for name, data in [('maps/tiny.bsp', bsp), ('textures/test/wall.png', tiny_png)]:
        info = zipfile.ZipInfo(name, date_time=(2024, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_DEFLATED
        z.writestr(info, data)

# --- Strict parsing and caps (docs/scenes.md, "Strict input"), for the
# command-line checks in tests/CMakeLists.txt.
# An OBJ whose second vertex has a word that is not a number.
write('garbage_number.obj', "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n")
# The cube's scene with a UTF-8 byte-order mark, and one whose camera looks away.
write('bom_scene.json', b'\xef\xbb\xbf' + json.dumps({
    "mesh": "cube.obj",
    "camera": {"eye": [3, 2, 4], "target": [0, 0, 0], "up": [0, 1, 0], "fov_y": 50},
    "resolution": [64, 48]}, indent=1).encode() + b"\n")
write('looking_away.json', json.dumps({
    "mesh": "cube.obj",
    "camera": {"eye": [3, 2, 4], "target": [6, 4, 8], "up": [0, 1, 0], "fov_y": 50},
    "resolution": [64, 48]}, indent=1) + "\n")
# glTF variants of the quad: an extension cdsim cannot read is required; only
# points; a node hierarchy whose scales multiply beyond the range of a float.
draco = gltf({"uri": "checker_64x32.png"})
draco["extensionsUsed"] = ["KHR_draco_mesh_compression"]
draco["extensionsRequired"] = ["KHR_draco_mesh_compression"]
write('draco_required.gltf', json.dumps(draco, indent=1) + "\n")
points = gltf({"uri": "checker_64x32.png"})
points["meshes"][0]["primitives"][0]["mode"] = 0
write('points_only.gltf', json.dumps(points, indent=1) + "\n")
overflow = gltf({"uri": "checker_64x32.png"})
overflow["scenes"] = [{"nodes": [0]}]
overflow["nodes"] = [{"children": [1], "scale": [1e30, 1e30, 1e30]},
                     {"name": "inner", "mesh": 0, "scale": [1e30, 1e30, 1e30]}]
write('scale_overflow.gltf', json.dumps(overflow, indent=1) + "\n")
# A .pk3 with explicit directory entries, as some zip tools write them.
with zipfile.ZipFile('folders.pk3', 'w', zipfile.ZIP_DEFLATED) as z:
    for name, data in [('maps/', b''), ('maps/tiny.bsp', bsp)]:
        info = zipfile.ZipInfo(name, date_time=(2024, 1, 1, 0, 0, 0))
        info.compress_type = zipfile.ZIP_STORED if name.endswith('/') else zipfile.ZIP_DEFLATED
        if name.endswith('/'):
            info.external_attr = 0o40755 << 16 | 0x10
        z.writestr(info, data)

# --- Robustness, second round (issue 40): inputs that used to be read wrong
# or refused, for the command-line checks in tests/CMakeLists.txt.
# Faces without texture coordinates (they used to become (0, 0)), and a
# negative vt index past the start (it used to be accepted).
write('no_texcoords.obj', "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n")
write('no_texcoords_default.json', json.dumps({
    "mesh": "no_texcoords.obj", "missing_texcoord": [0.5, 0.5],
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov_y": 60}, "resolution": [64, 48]}, indent=1) + "\n")
write('negative_past_start.obj', "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/-9 2/-8 3/-7\n")
# Legal OBJ that used to be refused: a backslash continuation and a face of
# 300 corners (a disc).
disc = ["# a disc of 300 corners, its face continued over two lines", "vt 0.5 0.5"]
disc += ["v %.6f %.6f 0" % (math.cos(2 * math.pi * k / 300), math.sin(2 * math.pi * k / 300)) for k in range(300)]
corners = ["%d/1" % (k + 1) for k in range(300)]
disc.append("f " + " ".join(corners[:150]) + " \\")
disc.append("  " + " ".join(corners[150:]))
write('disc_300_corners.obj', "\n".join(disc) + "\n")
# A scene whose "camera" is given twice.
write('duplicate_camera.json', """{
 "mesh": "cube.obj",
 "camera": {"eye": [3, 2, 4], "target": [0, 0, 0], "fov_y": 50},
 "camera": {"eye": [0, 0, 9], "target": [0, 0, 0], "fov_y": 50}
}
""")
# glTF variants of the quad: texCoord 1 without TEXCOORD_1; a projective node
# matrix; a zero quaternion; primitive mode 9; Draco required with accessors
# left without buffer views; positions as a sparse accessor without a buffer view.
variant = gltf({"uri": "checker_64x32.png"})
variant["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1
write('texcoord1_missing.gltf', json.dumps(variant, indent=1) + "\n")
variant = gltf({"uri": "checker_64x32.png"})
variant["nodes"][0] = {"mesh": 0, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, -0.25, 0, 0, -3, 1]}
write('projective_matrix.gltf', json.dumps(variant, indent=1) + "\n")
variant = gltf({"uri": "checker_64x32.png"})
variant["nodes"][0]["rotation"] = [0, 0, 0, 0]
write('zero_quaternion.gltf', json.dumps(variant, indent=1) + "\n")
variant = gltf({"uri": "checker_64x32.png"})
variant["meshes"][0]["primitives"][0]["mode"] = 9
write('mode9.gltf', json.dumps(variant, indent=1) + "\n")
variant = gltf({"uri": "checker_64x32.png"})
for accessor in variant["accessors"]:
    del accessor["bufferView"]
variant["extensionsUsed"] = ["KHR_draco_mesh_compression"]
variant["extensionsRequired"] = ["KHR_draco_mesh_compression"]
write('draco_accessors.gltf', json.dumps(variant, indent=1) + "\n")
variant = gltf({"uri": "checker_64x32.png"})
sparse_data = struct.pack('<4H', 0, 1, 2, 3) + b''.join(struct.pack('<3f', *p) for p in positions)
variant["buffers"].append({"byteLength": len(sparse_data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(sparse_data).decode()})
variant["bufferViews"] += [{"buffer": 1, "byteOffset": 0, "byteLength": 8},
                           {"buffer": 1, "byteOffset": 8, "byteLength": 48}]
del variant["accessors"][0]["bufferView"]
variant["accessors"][0]["sparse"] = {"count": 4, "indices": {"bufferView": 3, "componentType": 5123},
                                     "values": {"bufferView": 4}}
write('sparse_positions.gltf', json.dumps(variant, indent=1) + "\n")
# The quad's .glb with its first chunk typed 'JSOX' (tinygltf said only "Invalid glTF binary.").
glb = bytearray(open('quad.glb', 'rb').read())
glb[19] = ord('X')
write('bad_chunk_type.glb', bytes(glb))
# A scene reached through a symbolic link, naming a mesh that is not there.
os.makedirs('linked', exist_ok=True)
write('linked/missing_mesh.json', json.dumps({
    "mesh": "nowhere.obj", "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov_y": 60}}, indent=1) + "\n")
if os.path.lexists('missing_mesh_link.json'):
    os.remove('missing_mesh_link.json')
os.symlink('linked/missing_mesh.json', 'missing_mesh_link.json')
