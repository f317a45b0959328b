// Scene and mesh loaders (docs/scenes.md): the fixtures in tests/data/scenes/
// load as written, every kind of malformed input is refused with an
// InputError that names the file and the field, and the OpenArena maps of
// Debian's openarena-081-maps load with their spawn points.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <set>
#include <sstream>

#include "pixel_coverage.hpp"
#include "evaluate.hpp"
#include "loaders/bsp.hpp"
#include "loaders/file_io.hpp"
#include "loaders/gltf.hpp"
#include "loaders/json_structure.hpp"
#include "loaders/limits.hpp"
#include "loaders/obj.hpp"
#include "loaders/pk3.hpp"
#include "loaders/scene_file.hpp"
#include "loaders/strict_text.hpp"
#include "scene.hpp"

namespace cdsim {
namespace {

const std::string kData = CDSIM_TEST_DATA "/scenes/";
const std::string kOpenArena = "/usr/share/games/openarena/baseoa/pak1-maps.pk3";
const glm::ivec2 kDefault{256, 256};

std::string read_text(const std::string& path) {
  const auto bytes = read_file_bytes(path);
  return std::string(bytes.begin(), bytes.end());
}

// Runs `load`, expects an InputError whose message contains every one of `parts`.
void expect_input_error(const std::function<void()>& load, std::initializer_list<std::string> parts) {
  try {
    load();
    ADD_FAILURE() << "no InputError; expected one mentioning '" << *parts.begin() << "'";
  } catch (const InputError& e) {
    for (const std::string& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
          << "message '" << e.what() << "' does not mention '" << part << "'";
  }
}

// SCOPED_TRACE names the line of the failing expectation.
#define EXPECT_INPUT_ERROR(...)  \
  do {                           \
    SCOPED_TRACE("");            \
    expect_input_error(__VA_ARGS__); \
  } while (0)

// ---------------------------------------------------------------- JSON scenes

TEST(JsonScene, CubeSceneLoadsWithItsCameraResolutionAndDefaultTextureSize) {
  const Scene scene = load_scene(kData + "cube_scene.json");
  EXPECT_EQ(scene.width, 640);
  EXPECT_EQ(scene.height, 360);
  EXPECT_GT(scene.triangles.size(), 0u);
  for (const char* part : {"cube_scene.json", "cube.obj", "eye (3, 2, 4)", "fov_y 50",
                           "default texture 128x128", "replay: --scene"})
    EXPECT_NE(scene.description.find(part), std::string::npos) << scene.description;
}

TEST(JsonScene, CommandLineOptionsOverrideTheFile) {
  SceneOptions options;
  options.resolution = "200x100";
  options.camera = "0,0,5,0,0,0,0,1,0,40";
  const Scene scene = load_scene(kData + "cube_scene.json", options);
  EXPECT_EQ(scene.width, 200);
  EXPECT_EQ(scene.height, 100);
  EXPECT_NE(scene.description.find("eye (0, 0, 5)"), std::string::npos) << scene.description;
}

TEST(JsonScene, ReplayStringReproducesTheScene) {
  const Scene first = load_scene(kData + "quad_scene.json");
  const std::string marker = "--camera ";
  const auto at = first.description.find(marker);
  ASSERT_NE(at, std::string::npos);
  const std::string camera =
      first.description.substr(at + marker.size(), first.description.find(' ', at + marker.size()) - at - marker.size());
  SceneOptions options;
  options.camera = camera;
  options.resolution = "320x240";
  const Scene again = load_scene(kData + "quad.glb", options);
  ASSERT_EQ(first.triangles.size(), again.triangles.size());
  for (size_t t = 0; t < first.triangles.size(); ++t)
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(first.triangles[t].vertex[i].x, again.triangles[t].vertex[i].x);
      EXPECT_EQ(first.triangles[t].vertex[i].w, again.triangles[t].vertex[i].w);
      EXPECT_EQ(first.triangles[t].vertex[i].u, again.triangles[t].vertex[i].u);
    }
}

TEST(JsonScene, EveryMalformedFieldIsNamed) {
  const std::string p = "bad.json";
  const auto parse = [&](const std::string& text) { return [=] { parse_scene_json(text, p); }; };
  const std::string camera = R"("camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60})";
  EXPECT_INPUT_ERROR(parse("{\"mesh\": "), {p, "not valid JSON at byte"});
  EXPECT_INPUT_ERROR(parse("[1, 2]"), {p, "expected a JSON object, found array"});
  EXPECT_INPUT_ERROR(parse("{}"), {p, "'mesh'", "missing"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": 3})"), {"'mesh'", "expected a string, found number"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": ""})"), {"'mesh'", "empty"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.json"})"), {"'mesh'", "another scene file"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "colour": 1})"), {"'colour'", "unknown field"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": 1})"), {"'camera'", "expected an object"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "fov_y": 60}})"),
                     {"'camera.target'", "missing"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,1], "target": [0,0,0], "fov_y": 60}})"),
                     {"'camera.eye'", "array of 3 numbers, found 2 elements"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,"x",1], "target": [0,0,0], "fov_y": 60}})"),
                     {"'camera.eye[1]'", "expected a number, found string"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1e999], "target": [0,0,0], "fov_y": 60}})"),
                     {p, "not valid JSON", "1e999"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 180}})"),
                     {p, "fov_y 180 is outside (0, 180)"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "target": [0,0,1], "fov_y": 60}})"),
                     {p, "eye and target coincide"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,1,0], "target": [0,0,0], "fov_y": 60}})"),
                     {p, "up vector is parallel"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60, "near": -1}})"),
                     {p, "near plane -1 is not positive"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60, "far": 1}})"),
                     {"'camera.far'", "unknown field"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "resolution": [0, 10]})"),
                     {"'resolution'", "element 0 is 0, outside 1..8192"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "resolution": [9000, 10]})"), {"'resolution'", "outside 1..8192"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "resolution": [1.5, 10]})"), {"'resolution'", "not an integer"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "resolution": "1920x1080"})"), {"'resolution'", "[width, height]"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "texture_size": [20000, 1]})"),
                     {"'texture_size'", "outside 1..16384"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.bsp", "spawn": -1})"), {"'spawn'", "integer"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.bsp", "spawn": 0, )" + camera + "}"),
                     {"'spawn'", "not both"});
}

TEST(JsonScene, MeshPathIsRelativeToTheSceneFile) {
  EXPECT_EQ(parse_scene_json(R"({"mesh": "m/a.obj"})", "dir/s.json").mesh, "dir/m/a.obj");
  EXPECT_EQ(parse_scene_json(R"({"mesh": "/abs/a.obj"})", "dir/s.json").mesh, "/abs/a.obj");
  EXPECT_EQ(parse_scene_json(R"({"mesh": "x.pk3:maps/a.bsp"})", "dir/s.json").mesh, "dir/x.pk3:maps/a.bsp");
}

TEST(JsonScene, MissingMeshFileIsNamed) {
  const std::string path = ::testing::TempDir() + "missing_mesh.json";
  std::ofstream(path) << R"({"mesh": "nowhere.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60}})";
  EXPECT_INPUT_ERROR([&] { load_scene(path); }, {"nowhere.obj", "cannot open"});
}

// ------------------------------------------------------- command-line options

TEST(SceneOptions, CameraAndResolutionOptionsAreChecked) {
  const Camera c = parse_camera_option("1,2,3,4,5,6,0,0,1,75", 0.5);
  EXPECT_EQ(c.eye, glm::dvec3(1, 2, 3));
  EXPECT_EQ(c.target, glm::dvec3(4, 5, 6));
  EXPECT_EQ(c.up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(c.fov_y_degrees, 75);
  EXPECT_EQ(c.near_plane, 0.5);
  EXPECT_EQ(parse_camera_option("1,2,3,4,5,6,0,0,1,75,2", 0.5).near_plane, 2);
  EXPECT_EQ(parse_camera_option(camera_option_text(c), 9).near_plane, 0.5);
  EXPECT_INPUT_ERROR([] { parse_camera_option("1,2,3", 1); }, {"--camera", "found 3"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("1,2,3,4,5,6,0,0,1,x", 1); }, {"--camera", "'x' is not a number"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("1,2,3,4,5,6,0,0,1,", 1); }, {"--camera", "'' is not a number"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("nan,2,3,4,5,6,0,0,1,60", 1); }, {"--camera", "'nan' is not a finite number"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("1e13,2,3,4,5,6,0,0,1,60", 1); }, {"--camera", "'1e13' is out of range"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("0x1,2,3,4,5,6,0,0,1,60", 1); }, {"--camera", "'0x1' is not a number"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("0,0,0,0,0,1,0,0,1,60", 1); }, {"--camera", "parallel"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("0,0,0,0,1,0,0,0,1,0", 1); }, {"--camera", "fov_y 0"});
  EXPECT_EQ(parse_resolution_option("640x480"), glm::ivec2(640, 480));
  EXPECT_INPUT_ERROR([] { parse_resolution_option("640"); }, {"--resolution", "not WxH"});
  EXPECT_INPUT_ERROR([] { parse_resolution_option("x480"); }, {"--resolution", "not WxH"});
  EXPECT_INPUT_ERROR([] { parse_resolution_option("640x-1"); }, {"--resolution", "outside 1..8192"});
  EXPECT_INPUT_ERROR([] { parse_resolution_option("99999999999999999999x1"); }, {"--resolution"});
}

TEST(SceneOptions, MeshWithoutCameraOrWithMisplacedOptionsIsRefused) {
  EXPECT_INPUT_ERROR([] { load_scene(kData + "cube.obj"); }, {"cube.obj", "needs a camera", "--camera"});
  SceneOptions spawn;
  spawn.spawn = 0;
  EXPECT_INPUT_ERROR([&] { load_scene(kData + "cube.obj", spawn); }, {"--spawn needs a Quake 3 map"});
  EXPECT_INPUT_ERROR([&] { load_scene("default", spawn); }, {"--spawn needs a Quake 3 map"});
  SceneOptions both = spawn;
  both.camera = "0,0,5,0,0,0,0,1,0,40";
  EXPECT_INPUT_ERROR([&] { load_scene(kData + "tiny.bsp", both); }, {"not both"});
  SceneOptions resolution;
  resolution.resolution = "64x64";
  EXPECT_INPUT_ERROR([&] { load_scene(CDSIM_TEST_DATA "/good.tri", resolution); },
                     {"good.tri", "do not apply"});
  EXPECT_INPUT_ERROR([&] { load_scene(kData + "cube.stl", resolution); }, {"cube.stl"});
}

TEST(SceneOptions, DefaultSceneTakesCameraAndResolution) {
  SceneOptions options;
  options.resolution = "320x180";
  const Scene scene = load_scene("default", options);
  EXPECT_EQ(scene.width, 320);
  EXPECT_GT(scene.triangles.size(), 100u);
  EXPECT_NE(scene.description.find("embedded corridor"), std::string::npos);
}

// ----------------------------------------------------------------------- OBJ

TEST(Obj, CubeHasTwelveTrianglesWithTextureSizesFromTheMaterials) {
  const LoadedObj obj = load_obj(kData + "cube.obj", kDefault);
  ASSERT_EQ(obj.mesh.triangles.size(), 12u);
  for (size_t t = 0; t < 8; ++t) EXPECT_EQ(obj.mesh.texture_size[t], glm::ivec2(64, 32)) << t;
  for (size_t t = 8; t < 12; ++t) EXPECT_EQ(obj.mesh.texture_size[t], kDefault) << t;
  // OBJ's t runs up the image; the loader flips it so that v runs down. The
  // first triangle has vt (0,0) (2,0) (2,2): t becomes 1, 1, -1, and the
  // whole-period shift (+1) makes the first corner (0, 2).
  EXPECT_EQ(obj.mesh.vertices[0].texcoord, glm::dvec2(0, 2));
  EXPECT_EQ(obj.mesh.vertices[2].texcoord, glm::dvec2(2, 0));
  EXPECT_NE(obj.summary.find("1 with a known texture size"), std::string::npos) << obj.summary;
}

TEST(Obj, MalformedFilesAreRefusedWithTheFaceNamed) {
  const auto load = [](const std::string& text) {
    return [=] { load_obj_from_memory(text, "", "bad.obj", kDefault); };
  };
  EXPECT_INPUT_ERROR(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
                     {"bad.obj:4: 'f' corner 3: '9' refers to vertex 9", "has 3"});
  EXPECT_INPUT_ERROR(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/5 3/1\n"),
                     {"bad.obj", "texture coordinate 5", "has 1"});
  EXPECT_INPUT_ERROR(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -7\n"),
                     {"bad.obj:4: 'f' corner 3: '-7' refers to vertex -7, before the first"});
  EXPECT_INPUT_ERROR(load("v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), {"bad.obj:1", "'1e999' is out of range"});
  // Nothing to draw is not an error: an empty mesh.
  EXPECT_EQ(load_obj_from_memory("", "", "empty.obj", kDefault).mesh.triangles.size(), 0u);
  EXPECT_EQ(load_obj_from_memory("v 0 0 0\nf 1 1\n", "", "line.obj", kDefault).mesh.triangles.size(), 0u);
  EXPECT_INPUT_ERROR([] { load_obj(kData + "no_such.obj", kDefault); }, {"no_such.obj", "cannot open"});
}

// Two inputs on which tinyobjloader 2.0.0rc10 itself has undefined behaviour
// (found by fuzz_obj): the loader refuses the first and hides the second.
TEST(Obj, InputsThatTinyobjloaderMishandlesAreStoppedFirst) {
  EXPECT_INPUT_ERROR([] { load_obj_from_memory("v 1e2147483649 0 0\n", "", "exp.obj", kDefault); },
                     {"exp.obj:1", "exponent of 10 digits"});
  EXPECT_INPUT_ERROR([] { load_obj_from_memory("mtllib m.mtl\n", "newmtl a\nNs 1.5e-99999999\n", "m.obj", kDefault); },
                     {"m.mtl:2", "exponent of 8 digits"});
  const LoadedObj obj = load_obj_from_memory("vw 2 11111111111111111111111111111111111111 0.5\n"
                                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\nl 1 2\n",
                                             "", "vw.obj", kDefault);
  EXPECT_EQ(obj.mesh.triangles.size(), 1u);
  EXPECT_NE(obj.summary.find("2 lines of unused directives skipped"), std::string::npos) << obj.summary;
}

TEST(Obj, MissingMaterialLibraryFallsBackToTheDefaultSize) {
  const LoadedObj obj = load_obj_from_memory(
      "mtllib nowhere.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n", "", "m.obj", {32, 16});
  ASSERT_EQ(obj.mesh.triangles.size(), 1u);
  EXPECT_EQ(obj.mesh.texture_size[0], glm::ivec2(32, 16));
}

// ---------------------------------------------------------------------- glTF

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) n |= uint32_t(uint8_t(bytes[i + 2]));
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

TEST(Gltf, QuadLoadsWithNodeTransformAndImageSize) {
  const LoadedGltf gltf = load_gltf(kData + "quad.gltf", kDefault);
  ASSERT_EQ(gltf.mesh.triangles.size(), 2u);
  EXPECT_EQ(gltf.mesh.texture_size[0], glm::ivec2(64, 32));
  for (const MeshVertex& v : gltf.mesh.vertices) EXPECT_EQ(v.position.z, -3.0);
  const LoadedGltf glb = load_gltf(kData + "quad.glb", kDefault);
  ASSERT_EQ(glb.mesh.triangles.size(), 2u);
  EXPECT_EQ(glb.mesh.texture_size[0], glm::ivec2(16, 8));
}

TEST(Gltf, MalformedFilesAreRefused) {
  const nlohmann::json good = nlohmann::json::parse(read_text(kData + "quad.gltf"));
  const auto load = [](const nlohmann::json& j) {
    const std::string text = j.dump();
    return [=] {
      load_gltf_from_memory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "bad.gltf",
                            kDefault);
    };
  };
  // The fixture's external image is not available in memory, and that is no error
  // (the texture size falls back); everything else about it is well-formed.
  nlohmann::json j = good;
  j["images"][0] = {{"uri", "data:image/png;base64," + base64(read_text(kData + "checker_64x32.png"))}};
  const std::string text = j.dump();
  EXPECT_EQ(load_gltf_from_memory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "m.gltf", kDefault)
                .mesh.texture_size[0],
            glm::ivec2(64, 32));

  j = good;
  j["accessors"][0]["count"] = 100;
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf", "POSITION", "accessor 0", "overrun buffer view 0"});
  j = good;
  j["accessors"][0]["count"] = 2;
  j["accessors"][1]["count"] = 2;
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf", "index 2 is 2, outside the 2 vertices"});
  j = good;
  j["nodes"][0]["children"] = {0};
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf", "node 0 is its own ancestor"});
  j = good;
  j["bufferViews"][0]["byteOffset"] = 1000;
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf"});
  j = good;
  j["meshes"][0]["primitives"][0]["material"] = 7;
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf"});
  j = good;
  j["buffers"][0]["uri"] = "outside.bin";
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf", "not a readable glTF"});
  j = good;
  // A matrix element beyond the range of a float is refused at its node.
  j["nodes"][0]["matrix"] = {1e308, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e308, 0, 0, 1};
  j["nodes"][0].erase("translation");
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: node 0", "matrix[0] is 1e+308"});
  // A NaN position inside the buffer.
  std::string buffer;
  const std::vector<float> floats = {std::nanf(""), 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0,
                                     0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<uint16_t> shorts = {0, 1, 2, 0, 2, 3, 0, 0};
  buffer.append(reinterpret_cast<const char*>(floats.data()), 4 * floats.size());
  buffer.append(reinterpret_cast<const char*>(shorts.data()), 2 * shorts.size());
  j = good;
  j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(buffer);
  j["buffers"][0]["byteLength"] = buffer.size();
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf", "mesh 0 primitive 0 triangle 0", "not finite"});
  j = good;
  j.erase("asset");
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf"});

  const std::string glb = read_text(kData + "quad.glb");
  for (size_t cut : {size_t(0), size_t(11), size_t(20), glb.size() / 2, glb.size() - 1})
    EXPECT_INPUT_ERROR(
        [&] { load_gltf_from_memory(reinterpret_cast<const uint8_t*>(glb.data()), cut, "cut.glb", kDefault); },
        {"cut.glb"});
  std::string wrong = glb;
  wrong[4] = 7;  // version 7
  EXPECT_INPUT_ERROR(
      [&] { load_gltf_from_memory(reinterpret_cast<const uint8_t*>(wrong.data()), wrong.size(), "v7.glb", kDefault); },
      {"v7.glb", "version 7 at byte 4"});
}

// ------------------------------------------------------------------------ BSP
// tiny.bsp (make_fixtures.py): header 144 bytes; shaders at 328 (72 each):
// wall, nodraw (SURF_NODRAW), missing; vertices at 544 (44 each): 0-3 wall
// quad, 4-12 patch control points, 13-15 mesh triangle; meshverts at 1248;
// faces at 1284 (104 each): polygon, 3x3 patch, mesh, nodraw polygon, billboard.

constexpr size_t kFaces = 1284, kFaceBytes = 104, kVertices = 544;

std::string tiny_bsp() { return read_text(kData + "tiny.bsp"); }

void put_i32(std::string& bytes, size_t at, int32_t value) { std::memcpy(&bytes[at], &value, 4); }

BspMap load_bsp_bytes(const std::string& bytes, const TextureSizeLookup& lookup = {}) {
  return load_bsp_from_memory(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), "t.bsp",
                              kDefault, lookup);
}

TEST(Bsp, TinyMapHasPolygonsMeshesAndTessellatedPatches) {
  const BspMap map = load_bsp_bytes(tiny_bsp());
  const int level = kPatchTessellationLevel;
  EXPECT_EQ(map.mesh.triangles.size(), size_t(2 + 2 * level * level + 1));
  EXPECT_EQ(map.stats.faces, 5u);
  EXPECT_EQ(map.stats.polygons, 1u);
  EXPECT_EQ(map.stats.patches, 1u);
  EXPECT_EQ(map.stats.meshes, 1u);
  EXPECT_EQ(map.stats.nodraw, 1u);
  EXPECT_EQ(map.stats.billboards, 1u);
  // A Bézier patch passes through its corner control points: the first
  // tessellated vertex is control point 0, (-64, 0, 128).
  const MeshVertex& first_patch_vertex = map.mesh.vertices[6];
  EXPECT_EQ(first_patch_vertex.position, glm::dvec3(-64, 0, 128));
  // At s = t = 1/2 the Bernstein weights are 1/4, 1/2, 1/4 in each direction;
  // the middle column bulges by 32 and the middle row by 16, so y = -16 - 8.
  bool found_centre = false;
  for (const MeshVertex& v : map.mesh.vertices)
    if (std::abs(v.position.x) < 1e-12 && std::abs(v.position.z - 160) < 1e-12) {
      EXPECT_NEAR(v.position.y, -(0.5 * 32 + 0.5 * 16), 1e-12);
      found_centre = true;
    }
  EXPECT_TRUE(found_centre);
}

TEST(Bsp, SpawnPointsAndTheirCameras) {
  const BspMap map = load_bsp_bytes(tiny_bsp());
  ASSERT_EQ(map.spawns.size(), 2u);
  EXPECT_EQ(map.spawns[0].classname, "info_player_deathmatch");
  EXPECT_EQ(map.spawns[0].origin, glm::dvec3(0, -200, 0));
  EXPECT_EQ(map.spawns[0].yaw_degrees, 90);
  EXPECT_EQ(map.spawns[1].classname, "info_player_start");
  EXPECT_EQ(map.spawns[1].pitch_degrees, 10);
  EXPECT_EQ(map.spawns[1].yaw_degrees, 45);
  const Camera c = spawn_camera(map.spawns[0], 1920, 1080);
  EXPECT_EQ(c.eye, glm::dvec3(0, -200, kSpawnLift + kViewHeight));
  EXPECT_NEAR(c.target.x, 0, 1e-9);
  EXPECT_GT(c.target.y, c.eye.y);  // yaw 90 looks along +y
  EXPECT_EQ(c.up, glm::dvec3(0, 0, 1));
  // 90 degrees horizontally at 16:9.
  EXPECT_NEAR(std::tan(glm::radians(c.fov_y_degrees) / 2) * 1920 / 1080, 1.0, 1e-12);
  const Camera looking_down = spawn_camera(map.spawns[1], 1920, 1080);
  EXPECT_LT(looking_down.target.z, looking_down.eye.z);
}

TEST(Bsp, TextureSizesComeFromTheLookup) {
  const BspMap map = load_bsp_bytes(tiny_bsp(), [](const std::string& shader) -> std::optional<glm::ivec2> {
    if (shader == "textures/test/wall") return glm::ivec2(512, 128);
    return std::nullopt;
  });
  EXPECT_EQ(map.mesh.texture_size.front(), glm::ivec2(512, 128));  // the wall polygon
  EXPECT_EQ(map.mesh.texture_size[2], kDefault);                     // the patch ("missing")
  EXPECT_EQ(map.stats.shaders, 2u);
  EXPECT_EQ(map.stats.shaders_sized, 1u);
}

TEST(Bsp, MalformedMapsAreRefusedWithLumpRecordAndOffset) {
  const std::string good = tiny_bsp();
  const auto with = [&](const std::function<void(std::string&)>& change) {
    std::string bytes = good;
    change(bytes);
    return [bytes] { load_bsp_bytes(bytes); };
  };
  EXPECT_INPUT_ERROR(with([](std::string& b) { b.resize(100); }), {"t.bsp", "truncated: 100 bytes"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { b[0] = 'V'; }), {"magic 'VBSP'", "not a Quake 3 BSP"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, 4, 47); }), {"version 47 at byte 4"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, 8 + 13 * 8, 1800); }),
                     {"lump 13 (faces)", "past the end"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, 8 + 10 * 8, -4); }),
                     {"lump 10 (vertexes)", "negative offset -4"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, 8 + 10 * 8 + 4, 700); }),
                     {"lump 10 (vertexes)", "not a multiple of the 44-byte record"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, 8 + 1 * 8 + 4, 0x7fffffff); }),
                     {"lump 1 (shaders)", "past the end"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces, 3); }),
                     {"face 0 at byte 1284", "shader index 3 is outside the 3 shaders"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces + 8, 9); }),
                     {"face 0", "type 9 is not"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces + 16, 1000); }),
                     {"face 0", "vertices 0..1000 are outside the 16 vertices"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces + 12, -1); }), {"face 0", "outside"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces + 24, 12); }),
                     {"face 0", "mesh vertices 0..12 are outside the 9 mesh vertices"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces + 24, 5); }),
                     {"face 0", "5 mesh vertices do not make whole triangles"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, 1248 + 4, 4); }),
                     {"face 0", "is 4, outside the face's 4 vertices"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces + kFaceBytes + 96, 4); }),
                     {"face 1", "patch of 4x3 control points"});
  EXPECT_INPUT_ERROR(with([](std::string& b) { put_i32(b, kFaces + kFaceBytes + 96, 5); }),
                     {"face 1", "patch of 5x3 control points, but the face has 9 vertices"});
  EXPECT_INPUT_ERROR(with([](std::string& b) {
                       const float nan = std::nanf("");
                       std::memcpy(&b[kVertices + 5 * 44 + 4], &nan, 4);
                     }),
                     {"lump 10 (vertexes): vertex 5 at byte 764 is not finite"});
  EXPECT_INPUT_ERROR(with([](std::string& b) {
                       const float inf = INFINITY;
                       std::memcpy(&b[kVertices + 2 * 44 + 12], &inf, 4);
                     }),
                     {"vertex 2", "not finite"});
}

TEST(Bsp, MalformedEntitiesAreRefusedWithTheByteOffset) {
  const auto parse = [](const std::string& text) { return [=] { parse_entities(text, "e"); }; };
  EXPECT_INPUT_ERROR(parse("{ \"a\" \"b\" "), {"e: byte", "entity 0 is not closed"});
  EXPECT_INPUT_ERROR(parse("{ \"a\" \"b }"), {"e: byte 6", "unterminated quoted value"});
  EXPECT_INPUT_ERROR(parse("{ \"a\" }"), {"expected a quoted value, found '}'"});
  EXPECT_INPUT_ERROR(parse("x"), {"e: byte 0", "expected '{' to open an entity"});
  EXPECT_EQ(parse_entities("// comment\n{ \"a\" \"b\" }\n{}", "e").size(), 2u);
  std::string bytes = tiny_bsp();
  const std::string origin = "\"0 -200 0\"";
  bytes.replace(bytes.find(origin), origin.size(), "\"0 -2x0 0\"");
  EXPECT_INPUT_ERROR([&] { load_bsp_bytes(bytes); },
                     {"entity 1 (info_player_deathmatch)", "\"origin\" \"0 -2x0 0\" is not 3 finite numbers"});
}

// Every prefix and a few thousand single-byte corruptions either load or throw
// InputError: nothing else escapes, and (under scripts/sanitize) nothing reads
// out of bounds.
TEST(Bsp, TruncationsAndByteFlipsNeverEscapeAsAnythingButInputError) {
  const std::string good = tiny_bsp();
  size_t refused = 0;
  for (size_t size = 0; size < good.size(); ++size) {
    try {
      load_bsp_bytes(good.substr(0, size));
    } catch (const InputError&) {
      ++refused;
    }
  }
  EXPECT_GT(refused, good.size() / 2);
  std::mt19937 random(5);
  for (int trial = 0; trial < 4000; ++trial) {
    std::string bytes = good;
    for (int flips = 0; flips < 1 + trial % 4; ++flips)
      bytes[random() % bytes.size()] = static_cast<char>(random());
    try {
      load_bsp_bytes(bytes);
    } catch (const InputError&) {
    }
  }
}

// ------------------------------------------------------------------------ pk3

TEST(Pk3, MapAndTextureSizeComeFromTheArchive) {
  const BspMap map = load_bsp(kData + "tiny.pk3:maps/tiny.bsp", kDefault);
  EXPECT_EQ(map.mesh.texture_size.front(), glm::ivec2(16, 8));  // textures/test/wall.png
  EXPECT_EQ(map.stats.shaders_sized, 1u);
  EXPECT_EQ(map.spawns.size(), 2u);
  // Case does not matter inside a pk3, as in Quake.
  EXPECT_EQ(load_bsp(kData + "tiny.pk3:MAPS/Tiny.bsp", kDefault).mesh.triangles.size(),
            map.mesh.triangles.size());
  // The loose file finds its texture in the .pk3 beside it, as Quake's search path does.
  EXPECT_EQ(load_bsp(kData + "tiny.bsp", kDefault).mesh.texture_size.front(), glm::ivec2(16, 8));
  // A shader without an image anywhere falls back to the default size.
  EXPECT_EQ(load_bsp(kData + "tiny.bsp", kDefault).mesh.texture_size[2], kDefault);
}

TEST(Pk3, MalformedArchivesAndMissingEntriesAreRefused) {
  EXPECT_INPUT_ERROR([] { load_bsp(kData + "tiny.pk3:maps/other.bsp", kDefault); },
                     {"tiny.pk3", "no entry 'maps/other.bsp'", "holds 1 maps: maps/tiny.bsp"});
  EXPECT_INPUT_ERROR([] { load_bsp(kData + "none.pk3:maps/x.bsp", kDefault); },
                     {"none.pk3", "cannot open"});
  EXPECT_INPUT_ERROR([] { load_bsp(kData + "cube.obj.pk3:maps/x.bsp", kDefault); }, {"cube.obj.pk3"});
  EXPECT_INPUT_ERROR([] { load_scene(kData + "tiny.pk3"); }, {"tiny.pk3", "name a map inside"});
  std::vector<uint8_t> zip = read_file_bytes(kData + "tiny.pk3");
  // libzip reads an empty file as an empty archive: no entries, so no map.
  EXPECT_TRUE(Pk3Archive::open_memory({}, "empty.pk3").entries().empty());
  for (size_t cut : {size_t(10), size_t(100), zip.size() / 2, zip.size() - 1}) {
    SCOPED_TRACE(cut);
    EXPECT_INPUT_ERROR([&] { Pk3Archive::open_memory({zip.begin(), zip.begin() + std::ptrdiff_t(cut)}, "cut.pk3"); },
                       {"cut.pk3", "cannot open as a zip"});
  }
  // A corrupt compressed stream: the CRC (or inflate) check refuses it.
  std::vector<uint8_t> flipped = zip;
  flipped[60] ^= 0xff;
  try {
    const Pk3Archive archive = Pk3Archive::open_memory(flipped, "flip.pk3");
    EXPECT_INPUT_ERROR([&] { archive.read("maps/tiny.bsp"); }, {"flip.pk3:maps/tiny.bsp", "corrupt entry"});
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("flip.pk3"), std::string::npos);
  }
}

TEST(Pk3, SceneFromTinyMapSpawn) {
  SceneOptions options;
  options.spawn = 1;
  options.resolution = "320x200";
  const Scene scene = load_scene(kData + "tiny.pk3:maps/tiny.bsp", options);
  EXPECT_GT(scene.triangles.size(), 0u);
  EXPECT_NE(scene.description.find("spawn 1 of 2 (entity 2, info_player_start"), std::string::npos)
      << scene.description;
  options.spawn = 2;
  EXPECT_INPUT_ERROR([&] { load_scene(kData + "tiny.pk3:maps/tiny.bsp", options); },
                     {"--spawn 2 but the map has 2 spawn points (0..1)"});
}

// ----------------------------------------------------------- OpenArena maps

TEST(OpenArena, EveryMapLoadsWithSpawnPoints) {
  if (!std::ifstream(kOpenArena)) GTEST_SKIP() << kOpenArena << " is missing (Debian package openarena-081-maps)";
  const Pk3Archive archive = Pk3Archive::open_file(kOpenArena);
  size_t maps = 0, patches = 0;
  for (const std::string& entry : archive.entries()) {
    if (!ends_with_ignoring_case(entry, ".bsp")) continue;
    const BspMap map = load_bsp(kOpenArena + ":" + entry, kDefault);
    ++maps;
    patches += map.stats.patches;
    EXPECT_GT(map.mesh.triangles.size(), 1000u) << entry;
    EXPECT_GT(map.stats.polygons, 0u) << entry;
    EXPECT_FALSE(map.spawns.empty()) << entry;
  }
  EXPECT_EQ(maps, 50u);
  EXPECT_GT(patches, 100u);
}

TEST(OpenArena, ThreeMapsFromSpawnZeroReachTheUnit) {
  if (!std::ifstream(kOpenArena)) GTEST_SKIP() << kOpenArena << " is missing (Debian package openarena-081-maps)";
  for (const char* name : {"maps/oa_dm1.bsp", "maps/aggressor.bsp", "maps/oa_dm3.bsp"}) {
    SceneOptions options;
    options.spawn = 0;
    const Scene scene = load_scene(kOpenArena + ":" + name, options);
    EXPECT_GT(scene.triangles.size(), 500u) << name;
    const PreparedScene prepared = prepare(scene, Widths{});  // every triangle passes the unit's checks
    EXPECT_EQ(prepared.unit.size(), scene.triangles.size());
  }
}

// ------------------------------------------------------------- strict input
// docs/scenes.md, "Strict input": numbers, byte-order marks, unprintable bytes,
// files that are not regular files, size caps, scenes with nothing to draw.

const std::string kBom = "\xEF\xBB\xBF";

// A file in the test's temporary directory with `text`, its path returned.
std::string temp_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(StrictText, NumbersAreWholeFiniteAndInRange) {
  EXPECT_EQ(parse_number("1.5").value, 1.5);
  EXPECT_EQ(parse_number("+2").value, 2);
  EXPECT_EQ(parse_number("-0.25e1").value, -2.5);
  EXPECT_EQ(parse_number(".5").value, 0.5);
  EXPECT_TRUE(parse_number("1e-400").ok());  // underflow: a finite number
  for (const char* word : {"", "x", "1.5abc", "1,5", "0x10", "++1", "+-1", " 1", "1e", "1 2"})
    EXPECT_EQ(parse_number(word).problem, NumberProblem::kNotANumber) << word;
  for (const char* word : {"nan", "-nan", "inf", "-infinity", "nan(1)"})
    EXPECT_EQ(parse_number(word).problem, NumberProblem::kNotFinite) << word;
  EXPECT_EQ(parse_number("1e999").problem, NumberProblem::kOutOfRange);
  EXPECT_EQ(parse_number("-1e309").problem, NumberProblem::kOutOfRange);
  EXPECT_EQ(parse_number("4e38", 3.4e38).problem, NumberProblem::kOutOfRange);
  EXPECT_EQ(number_problem(parse_number("1e999"), "1e999"),
            "'1e999' is out of range: its magnitude exceeds 1.79769e+308");
  EXPECT_EQ(parse_integer("-12"), -12);
  EXPECT_EQ(parse_integer("+7"), 7);
  for (const char* word : {"", "1.0", "12x", "99999999999999999999", "0x1", "+-1", "++1"})
    EXPECT_FALSE(parse_integer(word).has_value()) << word;
}

TEST(StrictText, UnprintableBytesAreEscapedAndLongTextCut) {
  EXPECT_EQ(quote_bytes(std::string("a\0b", 3)), "'a\\x00b'");
  EXPECT_EQ(quote_bytes("\t\r\n\x7f\xff'"), "'\\t\\r\\n\\x7f\\xff\\''");
  EXPECT_EQ(quote_bytes(std::string(50, 'z'), 4), "'zzzz' (cut; 50 bytes in all)");
  EXPECT_EQ(without_utf8_bom(kBom + "v 1"), "v 1");
  EXPECT_EQ(without_utf8_bom("\xEF\xBB"), "\xEF\xBB");
}

TEST(TriangleList, EveryNumberIsStrictAndNamedWithLineAndValue) {
  const auto load = [](const std::string& text) { return [=] { load_triangle_text(text, "t.tri"); }; };
  const std::string good = "1 1 1 0 0  5 2 1 0 0  3 9 1 0 0\n";
  EXPECT_EQ(load_triangle_text(good, "t.tri").triangles.size(), 1u);
  EXPECT_INPUT_ERROR(load("\n1 1 1 0 0  5 2 1e999 0 0  3 9 1 0 0\n"),
                     {"t.tri:2: vertex 1 has a value out of range: w = '1e999'"});
  EXPECT_INPUT_ERROR(load("1 1 1 0 0  5 2 1 0 0  3 9 1 0 -inf\n"),
                     {"t.tri:1: vertex 2 has a non-finite value: v = '-inf'"});
  EXPECT_INPUT_ERROR(load("1 1 1 0 0  5 2 1 0 0  3 9 1.5abc 0 0\n"), {"t.tri:1: '1.5abc' is not a number"});
  EXPECT_INPUT_ERROR(load("1 1 1 0 0  5 2 1 0 0  3 9 0x1 0 0\n"), {"t.tri:1: '0x1' is not a number"});
  EXPECT_INPUT_ERROR(load("resolution 64.5 64\n" + good), {"t.tri:1: resolution '64.5' is not an integer"});
  EXPECT_INPUT_ERROR(load("resolution 64 99999999999999999999\n"), {"t.tri:1", "is not an integer"});
  EXPECT_INPUT_ERROR(load("resolution 64 64 1\n"), {"t.tri:1", "expected 'resolution W H'"});
}

// Before, the message stopped at the first NUL: "t.tri:1: '".
TEST(TriangleList, NulAndOtherUnprintableBytesAreShownEscaped) {
  try {
    load_triangle_text(std::string("\0\0\0 1 1 0 0  5 2 1 0 0  3 9 1 0 0\n", 34), "t.tri");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "t.tri:1: '\\x00\\x00\\x00' is not a number");
  }
  EXPECT_INPUT_ERROR([] { load_triangle_text("1 1 1 0 0  5 2 1 0 0  3 9 1 0 \x1b[31m\n", "t.tri"); },
                     {"t.tri:1: '\\x1b[31m' is not a number"});
}

TEST(TriangleList, ByteOrderMarkAndCarriageReturnsChangeNothing) {
  const std::string text = "resolution 64 48\n1 1 1 0 0  40 2 1 0 0  3 40 1 10 10\n";
  std::string crlf;
  for (const char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const Scene plain = load_triangle_text(text, "t.tri");
  for (const std::string& variant : {kBom + text, kBom + crlf}) {
    const Scene scene = load_scene(temp_file("bom.tri", variant));
    EXPECT_EQ(scene.width, 64);
    EXPECT_EQ(scene.height, 48);
    ASSERT_EQ(scene.triangles.size(), 1u);
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(scene.triangles[0].vertex[i].x, plain.triangles[0].vertex[i].x);
      EXPECT_EQ(scene.triangles[0].vertex[i].v, plain.triangles[0].vertex[i].v);
    }
  }
  // A mark anywhere but at the start is no number.
  EXPECT_INPUT_ERROR([&] { load_triangle_text("\n" + kBom + "1 1 1 0 0  40 2 1 0 0  3 40 1 10 10\n", "t.tri"); },
                     {"t.tri:2: '\\xef\\xbb\\xbf1' is not a number"});
}

TEST(TriangleList, ListWithoutTrianglesIsRefused) {
  EXPECT_INPUT_ERROR([] { load_scene(temp_file("none.tri", "# nothing\nresolution 8 8\n")); },
                     {"none.tri: no triangle to draw", "no triangle lines"});
  EXPECT_INPUT_ERROR([] { load_scene(temp_file("blank.tri", "")); }, {"blank.tri: no triangle to draw"});
}

TEST(Files, DirectoriesAndDevicesAreRefusedBeforeOpening) {
  const std::string folder = ::testing::TempDir() + "folder.obj";
  std::filesystem::create_directories(folder);
  EXPECT_INPUT_ERROR([&] { read_file_bytes(folder); }, {"folder.obj: is a directory, not a regular file"});
  EXPECT_INPUT_ERROR([] { read_file_bytes("/dev/zero"); }, {"/dev/zero: is a character device"});
  SceneOptions camera;
  camera.camera = "0,0,5,0,0,0,0,1,0,60";
  EXPECT_INPUT_ERROR([&] { load_scene(folder, camera); }, {"folder.obj: is a directory"});
  EXPECT_INPUT_ERROR([] { load_scene("/dev/null"); }, {"/dev/null: is a character device"});
  EXPECT_INPUT_ERROR([] { load_scene(CDSIM_TEST_DATA); }, {"data: is a directory"});
  EXPECT_INPUT_ERROR([&] { load_scene(temp_file("dir.json", R"({"mesh": "folder.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60}})")); },
                     {"folder.obj: is a directory"});
  const std::string pk3_folder = ::testing::TempDir() + "folder.pk3";
  std::filesystem::create_directories(pk3_folder);
  EXPECT_INPUT_ERROR([&] { Pk3Archive::open_file(pk3_folder); }, {"folder.pk3: is a directory"});
  EXPECT_INPUT_ERROR([] { Pk3Archive::open_file("/dev/zero"); }, {"/dev/zero: is a character device"});
  // A directory entry inside an archive (folders.pk3 holds "maps/" explicitly).
  EXPECT_INPUT_ERROR([] { load_bsp(kData + "folders.pk3:maps/", kDefault); },
                     {"folders.pk3:maps/: is a directory in the archive"});
  EXPECT_EQ(load_bsp(kData + "folders.pk3:maps/tiny.bsp", kDefault).spawns.size(), 2u);
}

// Sparse files: the cap is checked from the size before any byte is read.
TEST(Files, EveryFormatHasASizeCapStatedInTheMessage) {
  for (const char* name : {"big.tri", "big.obj", "big.json", "big.gltf", "big.glb", "big.bsp"}) {
    const std::string path = ::testing::TempDir() + name;
    std::ofstream(path, std::ios::binary) << "x";
    std::filesystem::resize_file(path, limits::kMaxFileBytes + 1);
    SceneOptions camera;
    camera.camera = "0,0,5,0,0,0,0,1,0,60";
    const std::string spec = path;
    EXPECT_INPUT_ERROR([&] { load_scene(spec, std::string(name) == "big.tri" ? SceneOptions{} : camera); },
                       {name, "larger than the 256 MiB cap on input files", "268435457 bytes"});
    std::filesystem::remove(path);
  }
}

TEST(Obj, EveryNumberOfVertexTexcoordNormalAndFaceLinesIsChecked) {
  const auto load = [](const std::string& text) {
    return [=] { load_obj_from_memory(text, "", "bad.obj", kDefault); };
  };
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_INPUT_ERROR(load("v 0 0 0\nv 1 abc 0\n"), {"bad.obj:2: 'v' number 2: 'abc' is not a number"});
  EXPECT_INPUT_ERROR(load("v 0 0 0\nv 1 1.5abc 0\n"), {"bad.obj:2: 'v' number 2: '1.5abc' is not a number"});
  EXPECT_INPUT_ERROR(load("v 1 2\n"), {"bad.obj:1: 'v' expects x y z [w] [r g b] (3 to 7 numbers), found 2"});
  EXPECT_INPUT_ERROR(load("v 1e39 0 0\n"), {"bad.obj:1: 'v' number 1: '1e39' is out of range", "floats"});
  EXPECT_INPUT_ERROR(load("v 0 nan 0\n"), {"bad.obj:1: 'v' number 2: 'nan' is not a finite number"});
  EXPECT_INPUT_ERROR(load(tri + "vt 0.5 inf\n"), {"bad.obj:4: 'vt' number 2: 'inf' is not a finite number"});
  EXPECT_INPUT_ERROR(load(tri + "vt 0 0 0 0\n"), {"bad.obj:4: 'vt' expects u [v [w]] (1 to 3 numbers), found 4"});
  EXPECT_INPUT_ERROR(load(tri + "vn 0 0 1x\n"), {"bad.obj:4: 'vn' number 3: '1x' is not a number"});
  EXPECT_INPUT_ERROR(load(tri + "vn 0 1\n"), {"bad.obj:4: 'vn' expects x y z (3 numbers), found 2"});
  EXPECT_INPUT_ERROR(load(tri + "f 1 2 x\n"), {"bad.obj:4: 'f' corner 3: 'x' is not a vertex reference"});
  EXPECT_INPUT_ERROR(load(tri + "f 1 2 0\n"), {"bad.obj:4: 'f' corner 3: '0'"});
  EXPECT_INPUT_ERROR(load(tri + "f 1 2 3.5\n"), {"bad.obj:4: 'f' corner 3: '3.5'"});
  EXPECT_INPUT_ERROR(load(tri + "f 1/1/1/1 2 3\n"), {"bad.obj:4: 'f' corner 1: '1/1/1/1'"});
  EXPECT_INPUT_ERROR(load(tri + "f 1/ 2 3\n"), {"bad.obj:4: 'f' corner 1: '1/'"});
  EXPECT_INPUT_ERROR(load(tri + "f 99999999999 2 3\n"), {"bad.obj:4: 'f' corner 1"});
  EXPECT_INPUT_ERROR(load(tri + "f\n"), {"bad.obj:4: 'f' has no corners"});
  EXPECT_INPUT_ERROR(load(tri + std::string("f 1 2\0 3\n", 10)), {"bad.obj:4: 'f' corner 2: '2\\x00'"});
  // Valid forms, signs and trailing comments pass.
  EXPECT_EQ(load_obj_from_memory(tri + "vt 0\nvt 1 0 0\nvn 0 0 1\nf 1/1/1 2/2/1 +3/-1 # comment\n", "", "ok.obj", kDefault)
                .mesh.triangles.size(),
            1u);
  EXPECT_EQ(load_obj_from_memory("v 0 0 0 1 # w\nv 1 0 0 1 0.5 0.5 0.5\nv 0 1 0 1 1 1\nvt 0 0\nf -3/-1 -2/-1 -1/-1\n", "", "ok.obj", kDefault)
                .mesh.triangles.size(),
            1u);
}

TEST(Obj, ByteOrderMarksOfObjAndMtlChangeNothing) {
  // The MTL starts with a directive, so that a mark left in place would hide the first material.
  const std::string obj = read_text(kData + "cube.obj");
  const std::string mtl = "newmtl checker\nKd 1 1 1\nmap_Kd checker_64x32.png\nnewmtl plain\nKd 0.5 0.5 0.5\n";
  const std::string dir = ::testing::TempDir() + "bom_cube/";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(kData + "checker_64x32.png", dir + "checker_64x32.png",
                             std::filesystem::copy_options::overwrite_existing);
  temp_file("bom_cube/cube.obj", kBom + obj);
  temp_file("bom_cube/cube.mtl", kBom + mtl);
  const LoadedObj plain = load_obj(kData + "cube.obj", kDefault);
  const LoadedObj marked = load_obj(dir + "cube.obj", kDefault);
  ASSERT_EQ(marked.mesh.triangles.size(), plain.mesh.triangles.size());
  EXPECT_EQ(marked.mesh.texture_size, plain.mesh.texture_size);  // the MTL's first material is read
  for (size_t i = 0; i < plain.mesh.vertices.size(); ++i)
    EXPECT_EQ(marked.mesh.vertices[i].position, plain.mesh.vertices[i].position) << i;
  EXPECT_EQ(marked.summary, plain.summary);
  // A mark left before a first 'v' would drop that vertex.
  EXPECT_EQ(load_obj_from_memory(kBom + "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n", "", "m.obj", kDefault)
                .mesh.triangles.size(),
            1u);
}

TEST(JsonScene, IntegersCoordinatesAndTextAreCheckedWithTheValueNamed) {
  const std::string p = "bad.json";
  const auto parse = [&](const std::string& text) { return [=] { parse_scene_json(text, p); }; };
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.bsp", "spawn": 18446744073709551615})"),
                     {"'spawn'", "expected an integer in 0..1000000, found 18446744073709551615"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.bsp", "spawn": 2.0})"), {"'spawn'", "found 2.0"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "resolution": [18446744073709551615, 10]})"),
                     {"'resolution'", "element 0 is 18446744073709551615, outside 1..8192"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [1e13,0,1], "target": [0,0,0], "fov_y": 60}})"),
                     {"'camera.eye[0]'", "10000000000000.0 is outside +-1e+12"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": "wide"}})"),
                     {"'camera.fov_y'", "expected a number, found string \"wide\""});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a\u0000.obj"})"), {"'mesh'", "\"a\\u0000.obj\" holds a control character"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": true})"), {"'mesh'", "expected a string, found boolean true"});
  const SceneFile marked = parse_scene_json(kBom + R"({"mesh": "a.obj", "resolution": [64, 48]})", "s.json");
  EXPECT_EQ(*marked.resolution, glm::ivec2(64, 48));
}

TEST(JsonScene, SceneWhoseMeshOrViewHoldsNoTriangleIsRefused) {
  EXPECT_INPUT_ERROR([] { load_scene(kData + "looking_away.json"); },
                     {"looking_away.json: no triangle to draw", "none of the mesh's 12 triangles", "--camera 3,2,4,6,4,8"});
  temp_file("empty_mesh.obj", "# nothing\nv 0 0 0\n");
  EXPECT_INPUT_ERROR([] { load_scene(temp_file("empty_mesh.json", R"({"mesh": "empty_mesh.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60}})")); },
                     {"empty_mesh.json: no triangle to draw: the OBJ", "0 triangles"});
  // The same file through the loader alone is an empty mesh, not an error.
  EXPECT_TRUE(load_obj(::testing::TempDir() + "empty_mesh.obj", kDefault).mesh.triangles.empty());
  EXPECT_GT(load_scene(kData + "bom_scene.json").triangles.size(), 0u);
}

TEST(Gltf, RequiredExtensionsUnusablePrimitivesAndOverflowingNodesAreRefused) {
  const nlohmann::json good = nlohmann::json::parse(read_text(kData + "quad.gltf"));
  const auto load = [](const nlohmann::json& j, const std::string& prefix = "") {
    const std::string text = prefix + j.dump();
    return [=] {
      load_gltf_from_memory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "bad.gltf", kDefault);
    };
  };
  nlohmann::json j = good;
  j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: requires the extension 'KHR_draco_mesh_compression'"});
  j["extensionsUsed"] = {"KHR_texture_transform"};
  j["extensionsRequired"] = {"KHR_texture_transform"};
  EXPECT_INPUT_ERROR(load(j), {"'KHR_texture_transform'"});
  j["extensionsUsed"] = {"KHR_materials_unlit"};
  j["extensionsRequired"] = {"KHR_materials_unlit"};
  EXPECT_NO_THROW(load(j)());
  j = good;
  j["meshes"][0]["primitives"][0]["mode"] = 1;  // lines
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: no usable primitive", "points or lines"});
  j = good;
  j["meshes"][0]["primitives"] = nlohmann::json::array();
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: no triangle to draw", "instances no mesh primitive"});
  j = good;
  j["nodes"][0].erase("mesh");
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: no triangle to draw"});
  // Scales that are each finite but multiply beyond a float, named by node.
  j = good;
  j["nodes"] = {{{"children", {1}}, {"scale", {1e30, 1e30, 1e30}}},
                {{"name", "inner"}, {"mesh", 0}, {"scale", {1e30, 1e30, 1e30}}}};
  j["scenes"][0]["nodes"] = {0};
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: node 1 'inner'", "overflows", "1.0000000000000001e+60"});
  j = good;
  j["nodes"][0]["scale"] = {1, 1e300, 1};
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: node 0: scale[1] is 1e+300"});
  // A transform within range that takes a vertex beyond it: named by node and triangle.
  j = good;
  j["nodes"][0]["matrix"] = {3e38, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 3e38, 0, 0, 1};
  j["nodes"][0].erase("translation");
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf: node 0 mesh 0 primitive 0 triangle 0", "is outside +-3.40282e+38"});
  // A byte-order mark before the JSON changes nothing.
  j = good;
  j["images"][0] = {{"uri", "data:image/png;base64," + base64(read_text(kData + "checker_64x32.png"))}};
  const std::string marked = kBom + j.dump();
  const LoadedGltf gltf =
      load_gltf_from_memory(reinterpret_cast<const uint8_t*>(marked.data()), marked.size(), "m.gltf", kDefault);
  EXPECT_EQ(gltf.mesh.triangles.size(), 2u);
  EXPECT_EQ(gltf.mesh.texture_size[0], glm::ivec2(64, 32));
}

TEST(Gltf, ExternalBuffersAreRegularFilesWithinTheCap) {
  nlohmann::json j = nlohmann::json::parse(read_text(kData + "quad.gltf"));
  const std::string dir = ::testing::TempDir() + "gltf_buffers/";
  std::filesystem::create_directories(dir + "folder.bin");
  j["buffers"][0]["uri"] = "folder.bin";
  temp_file("gltf_buffers/folder.gltf", j.dump());
  EXPECT_INPUT_ERROR([&] { load_gltf(dir + "folder.gltf", kDefault); }, {"folder.gltf", "folder.bin: is a directory"});
  const std::string big = dir + "big.bin";
  std::ofstream(big) << "x";
  std::filesystem::resize_file(big, limits::kMaxFileBytes + 1);
  j["buffers"][0]["uri"] = "big.bin";
  temp_file("gltf_buffers/big.gltf", j.dump());
  EXPECT_INPUT_ERROR([&] { load_gltf(dir + "big.gltf", kDefault); }, {"big.gltf", "big.bin", "256 MiB cap"});
  std::filesystem::remove(big);
}

TEST(Bsp, SpawnNumbersAreStrictAndTheirTextEscaped) {
  const std::string good = tiny_bsp(), origin = "\"0 -200 0\"";
  // Each the same length as the origin, so that no offset moves.
  for (const std::string bad : {"\"0 -20e 0\"", "\"0 0x10 0\"", "\"0 -inf 0\"", "\"0 1e13 0\"", "\"0 -20\x01 0\""}) {
    ASSERT_EQ(bad.size(), origin.size());
    std::string bytes = good;
    bytes.replace(bytes.find(origin), origin.size(), bad);
    EXPECT_INPUT_ERROR([&] { load_bsp_bytes(bytes); }, {"entity 1 (info_player_deathmatch)", "is not 3 finite numbers"});
  }
  std::string bytes = good;
  bytes.replace(bytes.find(origin), origin.size(), "\"0 -20\x01 0\"");
  EXPECT_INPUT_ERROR([&] { load_bsp_bytes(bytes); }, {"\"origin\" \"0 -20\\x01 0\" is not 3 finite numbers"});
}

// ------------------------------------------- Robustness, second round (inputs)

std::string nested(int depth) { return std::string(size_t(depth), '[') + std::string(size_t(depth), ']'); }

// A .glb of `json` and `bin`, each padded to 4 bytes as the format wants.
std::string make_glb(std::string json, std::string bin = "") {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin += '\0';
  std::string out = "glTF";
  const auto u32 = [&](size_t value) {
    const auto v = static_cast<uint32_t>(value);
    out.append(reinterpret_cast<const char*>(&v), 4);
  };
  u32(2);
  u32(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size()));
  u32(json.size());
  out += "JSON" + json;
  if (!bin.empty()) {
    u32(bin.size());
    out += std::string("BIN\0", 4) + bin;
  }
  return out;
}

LoadedGltf gltf_text(const std::string& text, const std::string& name = "t.gltf",
                     const std::optional<glm::dvec2>& missing = std::nullopt) {
  return load_gltf_from_memory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), name,
                               kDefault, missing);
}

nlohmann::json quad_gltf() { return nlohmann::json::parse(read_text(kData + "quad.gltf")); }

// The quad's JSON with `member` added to the top-level object, as text.
std::string with_member(const nlohmann::json& j, const std::string& member) {
  std::string text = j.dump();
  text.insert(text.size() - 1, "," + member);
  return text;
}

TEST(Json, NestingPastTheCapIsRefusedBeforeAnyParse) {
  const nlohmann::json quad = quad_gltf();
  // 20,000 levels overflowed the stack in tinygltf's recursive conversion of extras (exit 139).
  const std::string deep = with_member(quad, "\"extras\":" + nested(20000));
  EXPECT_INPUT_ERROR([&] { gltf_text(deep); }, {"t.gltf:1: JSON nested deeper than 512 levels", "before parsing"});
  const std::string deep_glb = make_glb(deep);
  EXPECT_INPUT_ERROR([&] { gltf_text(deep_glb, "t.glb"); }, {"t.glb (JSON chunk):1: JSON nested deeper than 512"});
  // The root object is level 1: extras 511 deep reach the cap and load, 512 deep pass it.
  EXPECT_EQ(gltf_text(with_member(quad, "\"extras\":" + nested(511))).mesh.triangles.size(), 2u);
  EXPECT_INPUT_ERROR([&] { gltf_text(with_member(quad, "\"extras\":" + nested(512))); }, {"deeper than 512"});
  // Brackets inside strings, after escaped quotes and backslashes, are text, not nesting.
  const std::string brackets = "\"extras\":\"\\\\\\\"" + std::string(1000, '[') + "\\\"" + std::string(1000, '{') + "\"";
  EXPECT_EQ(gltf_text(with_member(quad, brackets)).mesh.triangles.size(), 2u);
  // The line is counted, and the cap is a parameter other readers may pass.
  EXPECT_INPUT_ERROR([] { check_json_depth("{\"a\":\n [\n  [1]]}", "c.json", 2); }, {"c.json:3: JSON nested deeper than 2 levels", "byte 11"});
  EXPECT_NO_THROW(check_json_depth("{\"a\": \"[[[[\"}", "c.json", 1));
  // A scene file, and a scene file that names the deep glTF.
  EXPECT_INPUT_ERROR([] { parse_scene_json("{\"mesh\": \"a.obj\", \"x\": " + nested(20000) + "}", "s.json"); },
                     {"s.json:1: JSON nested deeper than 512 levels"});
  temp_file("deep.gltf", deep);
  EXPECT_INPUT_ERROR([] { load_scene(temp_file("deep_scene.json", R"({"mesh": "deep.gltf", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60}})")); },
                     {"deep.gltf:1: JSON nested deeper than 512 levels"});
}

TEST(JsonScene, DuplicateKeysAreRefusedWithTheirLines) {
  const auto parse = [](const std::string& text) { return [=] { parse_scene_json(text, "bad.json"); }; };
  const std::string camera = R"({"eye": [0,0,1], "target": [0,0,0], "fov_y": 60})";
  EXPECT_INPUT_ERROR(parse("{\n  \"mesh\": \"a.obj\",\n  \"camera\": " + camera + ",\n  \"camera\": " + camera + "\n}"),
                     {"bad.json:4: field 'camera' appears twice in one object (first at line 3)"});
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "eye": [0,0,2], "fov_y": 60}})"),
                     {"bad.json:1: field 'camera.eye' appears twice"});
  // Keys are compared as the parser reads them: \u0065 is 'e'.
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "m\u0065sh": "b.obj"})"), {"field 'mesh' appears twice"});
  // The same key in two objects is no repetition; a syntax error is reported as such.
  EXPECT_NO_THROW(parse(R"({"mesh": "a.obj", "resolution": [64, 48], "camera": {"eye": [0,0,1], "target": [0,0,0], "up": [0,1,0], "fov_y": 60}})")());
  EXPECT_INPUT_ERROR(parse(R"({"mesh": "a.obj", "mesh": })"), {"bad.json: not valid JSON at byte"});
  // glTF: the names within a JSON object must be unique (glTF 2.0 §3.2).
  std::string text = quad_gltf().dump();
  text.replace(text.find("\"mesh\":0"), 8, "\"mesh\":0,\"mesh\":0");
  EXPECT_INPUT_ERROR([&] { gltf_text(text); }, {"t.gltf:1: field 'nodes[0].mesh' appears twice"});
}

TEST(Obj, MissingTextureCoordinatesAreRefusedUnlessTheSceneGivesThem) {
  const auto load = [](const std::string& text) { return [=] { load_obj_from_memory(text, "", "bad.obj", kDefault); }; };
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.5\nvn 0 0 1\n";
  EXPECT_INPUT_ERROR(load(tri + "f 1 2 3\n"), {"bad.obj:6: 'f' corner 1: '1' has no texture coordinate", "missing_texcoord"});
  EXPECT_INPUT_ERROR(load(tri + "f 1/1 2/1 3\n"), {"bad.obj:6: 'f' corner 3: '3' has no texture coordinate"});
  EXPECT_INPUT_ERROR(load(tri + "f 1/1/1 2//1 3/1/1\n"), {"bad.obj:6: 'f' corner 2: '2//1' has no texture coordinate"});
  // Asked for explicitly, the missing ones take the given (s, t); the present one keeps its own.
  const LoadedObj obj = load_obj_from_memory(tri + "f 1/1 2 3\n", "", "d.obj", kDefault, glm::dvec2(0.5, 0.75));
  ASSERT_EQ(obj.mesh.vertices.size(), 3u);
  EXPECT_EQ(obj.mesh.vertices[0].texcoord, glm::dvec2(0.25, 0.5));  // t flipped: 1 - 0.5
  EXPECT_EQ(obj.mesh.vertices[1].texcoord, glm::dvec2(0.5, 0.75));
  EXPECT_EQ(obj.mesh.vertices[2].texcoord, glm::dvec2(0.5, 0.75));
  EXPECT_NE(obj.summary.find("2 corners without a texture coordinate given (0.5, 0.75)"), std::string::npos) << obj.summary;
  // Through a scene file: refused without the field, drawn with it.
  temp_file("no_vt.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  const std::string camera = R"("camera": {"eye": [0,0,3], "target": [0,0,0], "fov_y": 60})";
  EXPECT_INPUT_ERROR([&] { load_scene(temp_file("no_vt.json", "{\"mesh\": \"no_vt.obj\", " + camera + "}")); },
                     {"no_vt.obj:4: 'f' corner 1: '1' has no texture coordinate"});
  const Scene scene = load_scene(temp_file("no_vt_default.json", "{\"mesh\": \"no_vt.obj\", \"missing_texcoord\": [0.5, 0.5], " + camera + "}"));
  ASSERT_EQ(scene.triangles.size(), 1u);
  EXPECT_EQ(scene.triangles[0].vertex[0].u, 128.0);  // 0.5 of the default 256 texels
  EXPECT_INPUT_ERROR([] { parse_scene_json(R"({"mesh": "a.obj", "missing_texcoord": [0.5, "x"]})", "s.json"); },
                     {"s.json: field 'missing_texcoord[1]': expected a number"});
  EXPECT_INPUT_ERROR([] { parse_scene_json(R"({"mesh": "a.obj", "missing_texcoord": [0.5]})", "s.json"); },
                     {"s.json: field 'missing_texcoord': expected an array of 2 numbers"});
}

TEST(Obj, NegativeIndicesPastTheStartAreRefusedLikePositiveOnes) {
  const auto load = [](const std::string& text) { return [=] { load_obj_from_memory(text, "", "bad.obj", kDefault); }; };
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";
  EXPECT_INPUT_ERROR(load(tri + "f 1/-9 2/-8 3/-7\n"),
                     {"bad.obj:7: 'f' corner 1: '1/-9' refers to texture coordinate -9, before the first: only 3 'vt' lines precede this line"});
  EXPECT_INPUT_ERROR(load(tri + "f 1/9 2/8 3/7\n"), {"bad.obj:7: 'f' corner 1: '1/9' refers to texture coordinate 9, but the file has 3"});
  EXPECT_INPUT_ERROR(load(tri + "f -1/1 -2/1 -4/1\n"), {"bad.obj:7: 'f' corner 3: '-4/1' refers to vertex -4, before the first: only 3 'v' lines"});
  EXPECT_INPUT_ERROR(load(tri + "f 1/1/-1 2/1/-1 3/1/-1\n"), {"bad.obj:7: 'f' corner 1: '1/1/-1' refers to normal -1, before the first: only 0 'vn' lines"});
  // A negative index counts back from its face, so a vertex after the face does not make -4 valid.
  EXPECT_INPUT_ERROR(load(tri + "f -4/1 -2/1 -1/1\nv 5 5 5\n"), {"bad.obj:7: 'f' corner 1: '-4/1' refers to vertex -4"});
  const LoadedObj obj = load_obj_from_memory(tri + "f -3/-3 -2/-2 -1/-1\nv 5 5 5\n", "", "ok.obj", kDefault);
  ASSERT_EQ(obj.mesh.vertices.size(), 3u);
  EXPECT_EQ(obj.mesh.vertices[0].position, glm::dvec3(0, 0, 0));
  EXPECT_EQ(obj.mesh.vertices[2].position, glm::dvec3(0, 1, 0));
}

TEST(Obj, BackslashContinuesALineAndLineNumbersStayTrue) {
  const std::string text = "v 0 0 0\nv 1 0 \\\n  0\nv 0 1 0\nvt 0 0\nf 1/1 \\\n 2/1 \\\n 3/1\n";
  const LoadedObj obj = load_obj_from_memory(text, "", "c.obj", kDefault);
  ASSERT_EQ(obj.mesh.triangles.size(), 1u);
  EXPECT_EQ(obj.mesh.vertices[1].position, glm::dvec3(1, 0, 0));
  EXPECT_INPUT_ERROR([&] { load_obj_from_memory(text + "v 0 0 x\n", "", "c.obj", kDefault); }, {"c.obj:9: 'v' number 3: 'x'"});
  EXPECT_INPUT_ERROR([&] { load_obj_from_memory("v 0 0 0\nf 1 \\\r\n 2 x\r\n", "", "c.obj", kDefault); },
                     {"c.obj:2: 'f' corner 3: 'x'"});
  // A backslash inside a comment does not swallow the next line; one on the last line ends it.
  EXPECT_EQ(load_obj_from_memory("# see \\\n" + text + "f 1/1 2/1 3/1 \\", "", "c.obj", kDefault).mesh.triangles.size(), 2u);
}

TEST(Obj, FacesOfMoreThan255CornersAreFannedWhole) {
  constexpr int kCorners = 1000;
  std::string text = "vt 0 0\n", face = "f";
  for (int k = 0; k < kCorners; ++k) {
    const double angle = 2 * 3.14159265358979 * k / kCorners;
    text += fmt::format("v {} {} 0\n", std::cos(angle), std::sin(angle));
    face += fmt::format(" {}/1", k + 1);
  }
  const LoadedObj obj = load_obj_from_memory(text + face + "\n", "", "big.obj", kDefault);
  ASSERT_EQ(obj.mesh.triangles.size(), size_t(kCorners - 2));
  // Triangle k is the fan's (corner 0, corner k + 1, corner k + 2).
  for (size_t t : {size_t(0), size_t(254), size_t(255), size_t(kCorners - 3)}) {
    const double angle = 2 * 3.14159265358979 * double(t + 2) / kCorners;
    EXPECT_NEAR(obj.mesh.vertices[3 * t + 2].position.x, std::cos(angle), 1e-6) << t;
    EXPECT_NEAR(obj.mesh.vertices[3 * t + 2].position.y, std::sin(angle), 1e-6) << t;
  }
}

TEST(Gltf, MissingTexcoordSetIsRefusedUnlessTheSceneGivesIt) {
  nlohmann::json j = quad_gltf();
  j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); },
                     {"t.gltf: node 0 mesh 0 primitive 0: no TEXCOORD_1 attribute, which material 0's base colour texture reads (texCoord 1)"});
  j = quad_gltf();
  j["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
  j["meshes"][0]["primitives"][0].erase("material");
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"no TEXCOORD_0 attribute, which cdsim reads when the primitive has no texture"});
  const LoadedGltf given = gltf_text(j.dump(), "t.gltf", glm::dvec2(0.5, 0.25));
  ASSERT_EQ(given.mesh.vertices.size(), 6u);
  for (const MeshVertex& v : given.mesh.vertices) EXPECT_EQ(v.texcoord, glm::dvec2(0.5, 0.25));
  EXPECT_NE(given.summary.find("1 primitives without texture coordinates given (0.5, 0.25)"), std::string::npos) << given.summary;
}

TEST(Gltf, SparseAccessorsReplaceTheirElements) {
  // The quad's buffer, then sparse data: indices (uint16) 2 and 3, values two VEC3.
  const std::vector<float> base = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3, 2, 3};  // 6 triangle indices, then the sparse ones
  const std::vector<float> values = {1, 1, -1, -1, 1, -2};
  std::string buffer;
  buffer.append(reinterpret_cast<const char*>(base.data()), 4 * base.size());        // 0..80
  buffer.append(reinterpret_cast<const char*>(indices.data()), 2 * indices.size());  // 80..96
  buffer.append(reinterpret_cast<const char*>(values.data()), 4 * values.size());    // 96..120
  nlohmann::json j = quad_gltf();
  j["buffers"][0] = {{"byteLength", buffer.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer)}};
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 92}, {"byteLength", 4}});
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 24}});
  const nlohmann::json sparse = {{"count", 2},
                                 {"indices", {{"bufferView", 3}, {"componentType", 5123}}},
                                 {"values", {{"bufferView", 4}}}};
  j["accessors"][0]["sparse"] = sparse;
  j["accessors"][0].erase("min");
  j["accessors"][0].erase("max");
  const auto z_of = [](const LoadedGltf& g) {
    std::vector<double> z;
    for (const MeshVertex& v : g.mesh.vertices) z.push_back(v.position.z);
    return z;
  };
  // Triangles (0 1 2) and (0 2 3); the node moves z by -3.
  EXPECT_EQ(z_of(gltf_text(j.dump())), (std::vector<double>{-3, -3, -4, -3, -4, -5}));
  // Without a buffer view the base values are zeros.
  nlohmann::json no_base = j;
  no_base["accessors"][0].erase("bufferView");
  const LoadedGltf zeros = gltf_text(no_base.dump());
  EXPECT_EQ(zeros.mesh.vertices[0].position, glm::dvec3(0, 0, -3));
  EXPECT_EQ(zeros.mesh.vertices[2].position, glm::dvec3(1, 1, -4));
  // Indices that do not increase, or reach the count, are refused by name.
  j["bufferViews"][3]["byteOffset"] = 90;  // indices 3, 2
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"POSITION: accessor 0: sparse index 1 is 2: sparse indices must increase strictly"});
  j["bufferViews"][3]["byteOffset"] = 92;
  j["accessors"][0]["sparse"]["count"] = 5;
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"sparse.count 5 is outside 1..4"});
}

TEST(Gltf, ProjectiveMatricesAndNonUnitQuaternionsAreRefused) {
  nlohmann::json j = quad_gltf();
  j["nodes"][0].erase("translation");
  j["nodes"][0]["matrix"] = {1, 0, 0, 0.5, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1};
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"t.gltf: node 0: matrix's last row is (0.5, 0, 0, 1)", "must be affine"});
  j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 2};
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"matrix's last row is (0, 0, 0, 2)"});
  j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1};
  EXPECT_EQ(gltf_text(j.dump()).mesh.vertices[0].position, glm::dvec3(-1, -1, -3));
  j = quad_gltf();
  j["nodes"][0]["rotation"] = {0, 0, 0, 0};
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"t.gltf: node 0: rotation (0, 0, 0, 0) has length 0", "unit quaternion"});
  j["nodes"][0]["rotation"] = {0, 0, 0, 2};
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"rotation (0, 0, 0, 2) has length 2"});
  // A quarter turn about z written with four digits is a unit quaternion, normalised.
  j["nodes"][0]["rotation"] = {0, 0, 0.7071, 0.7071};
  const glm::dvec3 turned = gltf_text(j.dump()).mesh.vertices[0].position;  // (-1, -1, 0) turned
  EXPECT_NEAR(turned.x, 1, 1e-12);
  EXPECT_NEAR(turned.y, -1, 1e-12);
  EXPECT_EQ(turned.z, -3);
}

TEST(Gltf, UnknownPrimitiveModeAndBrokenGlbAreNamed) {
  nlohmann::json j = quad_gltf();
  j["meshes"][0]["primitives"][0]["mode"] = 9;
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"t.gltf: node 0 mesh 0 primitive 0: mode 9 is not a glTF primitive mode (0 to 6"});
  const std::string good = read_text(kData + "quad.glb");
  const auto load = [](const std::string& bytes) { return [=] { gltf_text(bytes, "b.glb"); }; };
  const auto put = [](std::string bytes, size_t at, uint32_t value) {
    std::memcpy(&bytes[at], &value, 4);
    return bytes;
  };
  uint32_t json_length = 0;
  std::memcpy(&json_length, &good[12], 4);
  const size_t bin_at = 20 + json_length;
  EXPECT_INPUT_ERROR(load(good.substr(0, 10)), {"b.glb: binary glTF (.glb): 10 bytes, shorter than the 12-byte header"});
  EXPECT_INPUT_ERROR(load(put(good, 8, uint32_t(good.size() + 4))),
                     {fmt::format("b.glb: binary glTF (.glb): the header's length at byte 8 is {} bytes, but the file has {}", good.size() + 4, good.size())});
  std::string wrong_type = good;
  wrong_type[19] = 'X';
  EXPECT_INPUT_ERROR(load(wrong_type), {"the first chunk (byte 12) has type 'JSOX'; it must be 'JSON'"});
  EXPECT_INPUT_ERROR(load(put(good, 12, 100000)), {"the JSON chunk's length at byte 12 is 100000 bytes"});
  EXPECT_INPUT_ERROR(load(put(good, bin_at, 100000)), {fmt::format("the BIN chunk's length at byte {} is 100000 bytes", bin_at)});
  std::string wrong_bin = good;
  wrong_bin[bin_at + 4] = 'X';
  EXPECT_INPUT_ERROR(load(wrong_bin), {fmt::format("the chunk at byte {} has type 'XIN\\x00'", bin_at)});
}

TEST(Gltf, RequiredExtensionIsNamedBeforeTheParseThatWouldFail) {
  // As Draco leaves it: accessors without buffer views, which tinygltf refuses first.
  nlohmann::json j = quad_gltf();
  for (auto& accessor : j["accessors"]) accessor.erase("bufferView");
  j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"t.gltf: requires the extension 'KHR_draco_mesh_compression'"});
  EXPECT_INPUT_ERROR([&] { gltf_text(make_glb(j.dump()), "t.glb"); }, {"t.glb (JSON chunk): requires the extension 'KHR_draco_mesh_compression'"});
  j["extensionsRequired"] = "KHR_draco_mesh_compression";
  EXPECT_INPUT_ERROR([&] { gltf_text(j.dump()); }, {"t.gltf: extensionsRequired is string, not an array of names"});
}

TEST(JsonScene, MissingMeshThroughASymlinkNamesTheSceneAndTheField) {
  const std::string dir = ::testing::TempDir() + "symlinked_scene/";
  std::filesystem::create_directories(dir + "real");
  temp_file("symlinked_scene/real/scene.json", R"({"mesh": "nowhere.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 60}})");
  std::filesystem::remove(dir + "link.json");
  std::filesystem::create_symlink("real/scene.json", dir + "link.json");
  EXPECT_INPUT_ERROR([&] { load_scene(dir + "link.json"); },
                     {"link.json: field 'mesh': " + dir + "nowhere.obj: cannot open",
                      "taken from the directory of " + dir + "link.json as named, not from that of the file it links to"});
  EXPECT_INPUT_ERROR([&] { load_scene(dir + "real/scene.json"); }, {"real/scene.json: field 'mesh': " + dir + "real/nowhere.obj: cannot open"});
}

// ------------------------------------------------------------ camera range

TEST(Camera, FieldOfViewAndNearPlaneOutsideTheExactRangeAreRefused) {
  EXPECT_INPUT_ERROR([] { parse_camera_option("0,0,1,0,0,0,0,1,0,1e-10", 0.05); },
                     {"--camera: fov_y 1e-10 is below 1e-06 degrees", "[1e-06, 180)"});
  EXPECT_INPUT_ERROR([] { parse_camera_option("0,0,1,0,0,0,0,1,0,60,1e-40", 0.05); },
                     {"--camera: near plane 1e-40 is below 1e-36", "[1e-36, 1e+12]"});
  EXPECT_INPUT_ERROR([] { parse_scene_json(R"({"mesh": "a.obj", "camera": {"eye": [0,0,1], "target": [0,0,0], "fov_y": 1e-16}})", "s.json"); },
                     {"s.json: camera: fov_y 1e-16 is below 1e-06 degrees"});
  EXPECT_NO_THROW(parse_camera_option("0,0,1,0,0,0,0,1,0,1e-6,1e-36", 0.05));
  EXPECT_NO_THROW(parse_camera_option(fmt::format("0,0,1,0,0,0,0,1,0,{},1e12", std::nextafter(180.0, 0.0)), 0.05));
}

// How many times the unit's coverage (top-left rule on snapped vertices)
// draws each pixel of `scene`.
std::vector<int> coverage_counts(const Scene& scene) {
  const Widths widths;
  std::vector<int> count(size_t(scene.width) * size_t(scene.height), 0);
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    const UnitTriangle triangle = to_unit(scene.triangles[i], widths, i);
    const EdgeSet edges = make_edges(triangle, widths.subpixel_bits);
    const PixelBox box = bounding_box(triangle, widths.subpixel_bits, scene.width, scene.height);
    for (int64_t y = box.y_lo; y <= box.y_hi; ++y)
      for (int64_t x = box.x_lo; x <= box.x_hi; ++x)
        if (covers(edges, x, y)) ++count[size_t(y) * size_t(scene.width) + size_t(x)];
  }
  return count;
}

// The front end's watertightness at the edges of the accepted camera range: a
// closed quad (two triangles sharing a diagonal) that covers the whole view,
// its corners far outside the guard band, draws every pixel exactly once.
TEST(Camera, ScreenFillingQuadCoversEveryPixelOnceAtTheExtremeCameras) {
  struct Extreme {
    double fov_y, near_plane, distance = 0;  // 0: three near planes, at least 1
  };
  const double widest = std::nextafter(180.0, 0.0);
  // The last two are scales: a mesh 1e-30 across just beyond the smallest
  // near plane, and one 1e37 across, near the largest w whose 1/w is a
  // normal float (beyond it the unit's input check refuses the triangle).
  for (const Extreme e : {Extreme{limits::kMinFovDegrees, 0.05}, Extreme{limits::kMinFovDegrees, limits::kMinNearPlane},
                          Extreme{limits::kMinFovDegrees, limits::kMaxCameraCoordinate}, Extreme{60, limits::kMinNearPlane},
                          Extreme{60, limits::kMaxCameraCoordinate}, Extreme{widest, 0.05}, Extreme{widest, 1e-3},
                          Extreme{60, limits::kMinNearPlane, 1e-30}, Extreme{limits::kMinFovDegrees, 0.05, 1e37}}) {
    SCOPED_TRACE(fmt::format("fov_y {} near {} distance {}", e.fov_y, e.near_plane, e.distance));
    const double distance = e.distance > 0 ? e.distance : std::max(3 * e.near_plane, 1.0);
    const double half_height = distance * std::tan(glm::radians(e.fov_y) / 2);
    // At least as large as its distance, so that at a narrow view its corners
    // lie ~1/tan(fov_y / 2) half-views off axis, where the clipping's rounding
    // grows (at 1e-15 degrees this quad loses a triangle); at a wide view 8
    // half-views, beyond the guard band (3) with room to spare.
    const double size = distance * std::max(1.0, 8 * half_height / distance);
    Mesh mesh;
    mesh.vertices = {{{-size, -size, -distance}, {0, 0}}, {{size, -size, -distance}, {1, 0}},
                     {{size, size, -distance}, {1, 1}}, {{-size, size, -distance}, {0, 1}}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    mesh.texture_size = {{256, 256}, {256, 256}};
    // The diagonal y = x crosses the view off its centre, at a slant.
    const double offset = std::min({half_height, distance, 0.1 * limits::kMaxCameraCoordinate});
    Camera camera;
    camera.eye = {0.3 * offset, 0.1 * offset, 0};
    camera.target = camera.eye + glm::dvec3(0, 0, -1);
    camera.fov_y_degrees = e.fov_y;
    camera.near_plane = e.near_plane;
    validate_camera(camera, "extreme");
    const std::vector<int> count = coverage_counts(project(mesh, camera, 96, 64, "quad"));
    size_t wrong = 0;
    for (int c : count) wrong += c != 1;
    EXPECT_EQ(wrong, 0u);
  }
}

// The two triangles of a shared edge walk it in opposite directions; clipping
// must give both the same crossing points to the last bit, or the snapped
// shared edge differs and pixels along it are drawn twice or not at all.
TEST(Camera, ClippedSharedEdgesAreBitwiseShared) {
  std::mt19937_64 random(40);
  std::uniform_real_distribution<double> spread(-1e6, 1e6);
  for (int trial = 0; trial < 200; ++trial) {
    SCOPED_TRACE(trial);
    // P and Q far to either side, so that the edge PQ crosses the view and
    // both guard-band planes; R and S on either side of it.
    const glm::dvec3 p(-1e6, spread(random) * 1e-6, -3 - std::fabs(spread(random)) * 1e-5);
    const glm::dvec3 q(1e6, spread(random) * 1e-6, -3 - std::fabs(spread(random)) * 1e-5);
    Mesh mesh;
    mesh.vertices = {{p, {0, 0}}, {q, {1, 0}}, {{0, 1e6, -3}, {0, 1}}, {q, {1, 0}}, {p, {0, 0}}, {{0, -1e6, -3}, {1, 1}}};
    mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    mesh.texture_size = {{256, 256}, {256, 256}};
    Camera camera;
    camera.eye = {0, 0, 0};
    camera.target = {0, 0, -1};
    camera.fov_y_degrees = 40;
    const Scene scene = project(mesh, camera, 640, 480, "edge");
    std::set<std::array<double, 3>> first, shared;
    for (const ScreenTriangle& t : scene.triangles)
      for (const ScreenVertex& v : t.vertex)
        if (t.origin == "mesh triangle 0") first.insert({v.x, v.y, v.w});
    for (const ScreenTriangle& t : scene.triangles)
      for (const ScreenVertex& v : t.vertex)
        if (t.origin == "mesh triangle 1" && first.count({v.x, v.y, v.w})) shared.insert({v.x, v.y, v.w});
    EXPECT_EQ(shared.size(), 2u);
  }
}

}  // namespace
}  // namespace cdsim
