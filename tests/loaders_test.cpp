// Scene and mesh loaders (docs/scenes.md): the fixtures in tests/data/scenes/
// load as written, every kind of malformed input is refused with an
// InputError that names the file and the field, and the OpenArena maps of
// Debian's openarena-081-maps load with their spawn points.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "evaluate.hpp"
#include "loaders/bsp.hpp"
#include "loaders/file_io.hpp"
#include "loaders/gltf.hpp"
#include "loaders/obj.hpp"
#include "loaders/pk3.hpp"
#include "loaders/scene_file.hpp"
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
  EXPECT_INPUT_ERROR([] { parse_camera_option("nan,2,3,4,5,6,0,0,1,60", 1); }, {"--camera", "non-finite"});
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
                     {"bad.obj", "face 0", "refers to vertex 9", "has 3"});
  EXPECT_INPUT_ERROR(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/5 3/1\n"),
                     {"bad.obj", "texture coordinate 5", "has 1"});
  EXPECT_INPUT_ERROR(load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -7\n"), {"bad.obj", "refers to vertex"});
  EXPECT_INPUT_ERROR(load("v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), {"bad.obj", "not finite"});
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
                                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nl 1 2\n",
                                             "", "vw.obj", kDefault);
  EXPECT_EQ(obj.mesh.triangles.size(), 1u);
  EXPECT_NE(obj.summary.find("2 lines of unused directives skipped"), std::string::npos) << obj.summary;
}

TEST(Obj, MissingMaterialLibraryFallsBackToTheDefaultSize) {
  const LoadedObj obj = load_obj_from_memory(
      "mtllib nowhere.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "", "m.obj", {32, 16});
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
  // x = 1e308 * 1 + 1e308 overflows to infinity at the quad's right edge.
  j["nodes"][0]["matrix"] = {1e308, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e308, 0, 0, 1};
  j["nodes"][0].erase("translation");
  EXPECT_INPUT_ERROR(load(j), {"bad.gltf", "not finite"});
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
                     {"none.pk3", "cannot open as a zip"});
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

}  // namespace
}  // namespace cdsim
