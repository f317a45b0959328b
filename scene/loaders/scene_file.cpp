#include "scene_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "bsp.hpp"
#include "file_io.hpp"
#include "gltf.hpp"
#include "json_structure.hpp"
#include "limits.hpp"
#include "obj.hpp"
#include "pk3.hpp"
#include "strict_text.hpp"

namespace cdsim {

namespace {

using nlohmann::json;

const char* json_type(const json& j) { return j.type_name(); }

class JsonFields {
 public:
  explicit JsonFields(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw InputError(fmt::format("{}: field '{}': {}", path_, field, what));
  }

  void only_keys(const json& object, const std::string& field, std::set<std::string> allowed) const {
    for (auto it = object.begin(); it != object.end(); ++it)
      if (!allowed.count(it.key()))
        fail(field.empty() ? it.key() : field + "." + it.key(),
             fmt::format("unknown field (expected one of: {})", fmt::join(allowed, ", ")));
  }

  // A finite number of magnitude at most `limit`.
  double number(const json& j, const std::string& field, double limit) const {
    if (!j.is_number())
      fail(field, fmt::format("expected a number, found {} {}", json_type(j), shown(j)));
    const double value = j.get<double>();
    if (!std::isfinite(value)) fail(field, fmt::format("{} is not finite", shown(j)));
    if (std::fabs(value) > limit) fail(field, fmt::format("{} is outside +-{:g}", shown(j), limit));
    return value;
  }

  // An integer in lo..hi (JSON integers only: 2.0 and 2e0 are refused).
  int64_t integer(const json& j, const std::string& field, int64_t lo, int64_t hi) const {
    const bool fits = j.is_number_integer() &&
                      !(j.is_number_unsigned() && j.get<uint64_t>() > uint64_t(INT64_MAX));
    if (!fits || j.get<int64_t>() < lo || j.get<int64_t>() > hi)
      fail(field, fmt::format("expected an integer in {}..{}, found {}", lo, hi, shown(j)));
    return j.get<int64_t>();
  }

  // The value as JSON text, ASCII only, cut short if long.
  static std::string shown(const json& j) {
    std::string text = j.dump(-1, ' ', true);
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    return text;
  }

  std::vector<double> numbers(const json& j, const std::string& field, size_t count, double limit) const {
    if (!j.is_array() || j.size() != count)
      fail(field, fmt::format("expected an array of {} numbers, found {}", count,
                              j.is_array() ? fmt::format("{} elements", j.size())
                                           : std::string(json_type(j))));
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i)
      out.push_back(number(j[i], fmt::format("{}[{}]", field, i), limit));
    return out;
  }

  glm::ivec2 size(const json& j, const std::string& field, int max) const {
    if (!j.is_array() || j.size() != 2)
      fail(field, fmt::format("expected [width, height], found {}",
                              j.is_array() ? fmt::format("{} elements", j.size())
                                           : std::string(json_type(j))));
    glm::ivec2 out;
    for (int i = 0; i < 2; ++i) {
      const json& e = j[size_t(i)];
      if (!e.is_number_integer())
        fail(field, fmt::format("element {} is not an integer: {}", i, shown(e)));
      // Compared as unsigned or signed as stored, so that 2^64 - 1 cannot wrap to -1.
      if (e.is_number_unsigned() ? (e.get<uint64_t>() < 1 || e.get<uint64_t>() > uint64_t(max))
                                 : (e.get<int64_t>() < 1 || e.get<int64_t>() > max))
        fail(field, fmt::format("element {} is {}, outside 1..{}", i, shown(e), max));
      out[i] = static_cast<int>(e.get<int64_t>());
    }
    return out;
  }

 private:
  std::string path_;
};

glm::dvec3 vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

std::string format_vec(const glm::dvec3& v) { return fmt::format("({}, {}, {})", v.x, v.y, v.z); }

}  // namespace

SceneFile parse_scene_json(const std::string& text, const std::string& path) {
  json root;
  const std::string_view body = without_utf8_bom(text);
  check_json_depth(body, path);
  try {
    root = json::parse(body.begin(), body.end());
  } catch (const json::parse_error& e) {
    throw InputError(fmt::format("{}: not valid JSON at byte {}: {}", path, e.byte, e.what()));
  } catch (const json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", path, e.what()));
  }
  // After the parse, so that a syntax error is reported as such first.
  check_json_unique_keys(body, path);
  const JsonFields fields(path);
  if (!root.is_object())
    throw InputError(fmt::format("{}: expected a JSON object, found {}", path, json_type(root)));
  fields.only_keys(root, "",
                   {"mesh", "camera", "resolution", "texture_size", "spawn", "missing_texcoord"});
  SceneFile out;
  if (!root.contains("mesh")) fields.fail("mesh", "missing (the path of an OBJ, glTF or BSP file)");
  if (!root["mesh"].is_string())
    fields.fail("mesh", fmt::format("expected a string, found {} {}", json_type(root["mesh"]),
                                    JsonFields::shown(root["mesh"])));
  const std::string mesh = root["mesh"].get<std::string>();
  if (mesh.empty()) fields.fail("mesh", "is empty");
  for (const char c : mesh)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      fields.fail("mesh", fmt::format("the path {} holds a control character",
                                      JsonFields::shown(root["mesh"])));
  if (ends_with_ignoring_case(mesh, ".json")) fields.fail("mesh", "a scene file cannot name another scene file");
  out.mesh = resolve_relative(path, mesh);
  if (root.contains("camera")) {
    const json& c = root["camera"];
    if (!c.is_object()) fields.fail("camera", fmt::format("expected an object, found {}", json_type(c)));
    fields.only_keys(c, "camera", {"eye", "target", "up", "fov_y", "near"});
    Camera camera;
    for (const char* required : {"eye", "target", "fov_y"})
      if (!c.contains(required)) fields.fail(fmt::format("camera.{}", required), "missing");
    const double limit = limits::kMaxCameraCoordinate;
    camera.eye = vec3(fields.numbers(c["eye"], "camera.eye", 3, limit));
    camera.target = vec3(fields.numbers(c["target"], "camera.target", 3, limit));
    if (c.contains("up")) camera.up = vec3(fields.numbers(c["up"], "camera.up", 3, limit));
    camera.fov_y_degrees = fields.number(c["fov_y"], "camera.fov_y", 180);
    if (c.contains("near")) camera.near_plane = fields.number(c["near"], "camera.near", limit);
    try {
      validate_camera(camera, "camera");
    } catch (const InputError& e) {
      throw InputError(fmt::format("{}: {}", path, e.what()));
    }
    out.camera = camera;
  }
  if (root.contains("spawn")) out.spawn = static_cast<int>(fields.integer(root["spawn"], "spawn", 0, 1000000));
  if (out.camera && out.spawn) fields.fail("spawn", "give a camera or a spawn point, not both");
  if (root.contains("resolution"))
    out.resolution = fields.size(root["resolution"], "resolution", limits::kMaxResolution);
  if (root.contains("texture_size"))
    out.texture_size = fields.size(root["texture_size"], "texture_size", limits::kMaxTextureSize);
  if (root.contains("missing_texcoord")) {
    const std::vector<double> st =
        fields.numbers(root["missing_texcoord"], "missing_texcoord", 2, kMaxMissingTexcoord);
    out.missing_texcoord = glm::dvec2(st[0], st[1]);
  }
  return out;
}

void validate_camera(const Camera& c, const std::string& where) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}: {}", where, what));
  };
  for (double v : {c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                   c.up.z, c.fov_y_degrees, c.near_plane})
    if (!std::isfinite(v)) fail("has a non-finite value");
  for (double v : {c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                   c.up.z, c.near_plane})
    if (std::fabs(v) > limits::kMaxCameraCoordinate)
      fail(fmt::format("coordinate {} is outside +-{:g}", v, limits::kMaxCameraCoordinate));
  if (!(c.fov_y_degrees > 0 && c.fov_y_degrees < 180))
    fail(fmt::format("fov_y {} is outside (0, 180) degrees", c.fov_y_degrees));
  if (c.fov_y_degrees < limits::kMinFovDegrees)
    fail(fmt::format("fov_y {} is below {:g} degrees: the front end's clipping, in double "
                     "precision, cannot keep coverage exact below it; use fov_y in [{:g}, 180) "
                     "(docs/scenes.md, \"Camera range\")",
                     c.fov_y_degrees, limits::kMinFovDegrees, limits::kMinFovDegrees));
  if (!(c.near_plane > 0)) fail(fmt::format("near plane {} is not positive", c.near_plane));
  if (c.near_plane < limits::kMinNearPlane)
    fail(fmt::format("near plane {} is below {:g}: a triangle clipped there would reach the unit "
                     "with 1/w beyond the largest float; use near in [{:g}, {:g}] "
                     "(docs/scenes.md, \"Camera range\")",
                     c.near_plane, limits::kMinNearPlane, limits::kMinNearPlane,
                     limits::kMaxCameraCoordinate));
  const glm::dvec3 forward = c.target - c.eye;
  const double length = glm::length(forward), up_length = glm::length(c.up);
  if (!(length > 0) || !std::isfinite(length)) fail("eye and target coincide (or are too far apart)");
  if (!(up_length > 0) || !std::isfinite(up_length)) fail("up vector is zero (or too long)");
  if (!(glm::length(glm::cross(forward / length, c.up / up_length)) > 1e-9))
    fail("up vector is parallel to the view direction");
}

Camera parse_camera_option(const std::string& text, double default_near) {
  std::vector<double> values;
  size_t start = 0;
  for (;;) {
    const size_t comma = text.find(',', start);
    const std::string_view word = std::string_view(text).substr(
        start, comma == std::string::npos ? std::string::npos : comma - start);
    const ParsedNumber parsed = parse_number(word, limits::kMaxCameraCoordinate);
    if (!parsed.ok())
      throw InputError(fmt::format("--camera: {} (expected ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_y[,near])",
                                   number_problem(parsed, word)));
    values.push_back(parsed.value);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (values.size() != 10 && values.size() != 11)
    throw InputError(fmt::format("--camera: expected 10 or 11 comma-separated numbers "
                                 "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_y[,near], found {}",
                                 values.size()));
  Camera camera;
  camera.eye = {values[0], values[1], values[2]};
  camera.target = {values[3], values[4], values[5]};
  camera.up = {values[6], values[7], values[8]};
  camera.fov_y_degrees = values[9];
  camera.near_plane = values.size() == 11 ? values[10] : default_near;
  validate_camera(camera, "--camera");
  return camera;
}

glm::ivec2 parse_resolution_option(const std::string& text) {
  const auto x = text.find_first_of("xX");
  std::optional<long long> w, h;
  if (x != std::string::npos) {
    w = parse_integer(std::string_view(text).substr(0, x));
    h = parse_integer(std::string_view(text).substr(x + 1));
  }
  if (!w || !h)
    throw InputError(fmt::format("--resolution: {} is not WxH (e.g. 1920x1080)", quote_bytes(text)));
  if (*w < 1 || *h < 1 || *w > limits::kMaxResolution || *h > limits::kMaxResolution)
    throw InputError(fmt::format("--resolution: {}x{} is outside 1..{}", *w, *h, limits::kMaxResolution));
  return {static_cast<int>(*w), static_cast<int>(*h)};
}

std::string camera_option_text(const Camera& c) {
  return fmt::format("{},{},{},{},{},{},{},{},{},{},{}", c.eye.x, c.eye.y, c.eye.z, c.target.x,
                     c.target.y, c.target.z, c.up.x, c.up.y, c.up.z, c.fov_y_degrees,
                     c.near_plane);
}

namespace {

enum class MeshKind { kObj, kGltf, kBsp, kUnknown };

MeshKind mesh_kind(const std::string& spec) {
  if (split_pk3_spec(spec) || ends_with_ignoring_case(spec, ".bsp")) return MeshKind::kBsp;
  if (ends_with_ignoring_case(spec, ".obj")) return MeshKind::kObj;
  if (ends_with_ignoring_case(spec, ".gltf") || ends_with_ignoring_case(spec, ".glb"))
    return MeshKind::kGltf;
  return MeshKind::kUnknown;
}

}  // namespace

bool is_scene_file(const std::string& spec) {
  return mesh_kind(spec) != MeshKind::kUnknown || ends_with_ignoring_case(spec, ".json") ||
         ends_with_ignoring_case(spec, ".pk3");
}

Scene load_scene_file(const std::string& spec, const SceneOptions& options) {
  if (ends_with_ignoring_case(spec, ".pk3"))
    throw InputError(fmt::format("{}: name a map inside the archive, as {}:maps/NAME.bsp", spec, spec));
  SceneFile file;
  std::string scene_source;
  if (ends_with_ignoring_case(spec, ".json")) {
    const std::vector<uint8_t> bytes = read_file_bytes(spec);
    file = parse_scene_json(std::string(bytes.begin(), bytes.end()), spec);
    scene_source = fmt::format("scene file {}: ", spec);
  } else {
    file.mesh = spec;
  }
  if (!options.camera.empty() && options.spawn >= 0)
    throw InputError("give --camera or --spawn, not both");
  const glm::ivec2 resolution = !options.resolution.empty()
                                    ? parse_resolution_option(options.resolution)
                                    : file.resolution.value_or(glm::ivec2(kDefaultWidth, kDefaultHeight));
  const glm::ivec2 texture = file.texture_size.value_or(glm::ivec2(kDefaultTextureSize));
  const bool is_default = spec == "default";
  const MeshKind kind = is_default ? MeshKind::kUnknown : mesh_kind(file.mesh);
  if (!is_default && kind == MeshKind::kUnknown)
    throw InputError(fmt::format("{}: mesh '{}' is not .obj, .gltf, .glb, .bsp or FILE.pk3:maps/NAME.bsp",
                                 spec, file.mesh));
  const double default_near = kind == MeshKind::kBsp ? kSpawnNearPlane : Camera{}.near_plane;
  std::optional<Camera> camera = file.camera;
  int spawn = file.spawn.value_or(-1);  // -1: none
  if (!options.camera.empty()) {
    camera = parse_camera_option(options.camera, default_near);
    spawn = -1;
  }
  if (options.spawn >= 0) {
    spawn = options.spawn;
    camera.reset();
  }

  if (!scene_source.empty() && kind != MeshKind::kUnknown) {
    // The loaders name only the mesh path; a scene file that names a missing
    // mesh should say which scene and field, and where relative paths start.
    const auto pk3 = split_pk3_spec(file.mesh);
    try {
      require_regular_file(pk3 ? pk3->first : file.mesh);
    } catch (const InputError& e) {
      std::string note;
      std::error_code error;
      if (std::filesystem::is_symlink(spec, error)) {
        const std::filesystem::path target = std::filesystem::canonical(spec, error);
        note = fmt::format(" (a relative mesh path is taken from the directory of {} as named, "
                           "not from that of the file it links to{})",
                           spec, error ? std::string() : ", " + target.string());
      }
      throw InputError(fmt::format("{}: field 'mesh': {}{}", spec, e.what(), note));
    }
  }
  Mesh mesh;
  std::string what;
  std::vector<BspSpawnPoint> spawns;
  switch (kind) {
    case MeshKind::kObj: {
      LoadedObj obj = load_obj(file.mesh, texture, file.missing_texcoord);
      mesh = std::move(obj.mesh);
      what = fmt::format("OBJ {} ({})", file.mesh, obj.summary);
      break;
    }
    case MeshKind::kGltf: {
      LoadedGltf gltf = load_gltf(file.mesh, texture, file.missing_texcoord);
      mesh = std::move(gltf.mesh);
      what = fmt::format("glTF {} ({})", file.mesh, gltf.summary);
      break;
    }
    case MeshKind::kBsp: {
      BspMap map = load_bsp(file.mesh, texture);
      mesh = std::move(map.mesh);
      spawns = std::move(map.spawns);
      const BspStats& s = map.stats;
      what = fmt::format(
          "Quake 3 BSP {} ({} faces: {} polygons, {} meshes, {} patches tessellated at level {}, "
          "{} billboards and {} nodraw faces skipped; {} triangles; {} of {} shaders with a known "
          "texture size; {} spawn points)",
          file.mesh, s.faces, s.polygons, s.meshes, s.patches, kPatchTessellationLevel,
          s.billboards, s.nodraw, mesh.triangles.size(), s.shaders_sized, s.shaders, spawns.size());
      break;
    }
    case MeshKind::kUnknown:
      mesh = default_mesh();
      what = "embedded corridor";
      if (!camera) camera = default_camera();
      break;
  }
  if (mesh.triangles.empty())
    throw InputError(fmt::format("{}: no triangle to draw: the {} has none", spec, what));
  std::string camera_from;
  if (spawn >= 0) {
    if (kind != MeshKind::kBsp)
      throw InputError(fmt::format("{}: --spawn needs a Quake 3 map (.bsp); give --camera", spec));
    if (spawns.empty())
      throw InputError(fmt::format("{}: the map has no info_player_deathmatch or info_player_start; "
                                   "give --camera",
                                   file.mesh));
    if (spawn >= int(spawns.size()))
      throw InputError(fmt::format("{}: --spawn {} but the map has {} spawn points (0..{})",
                                   file.mesh, spawn, spawns.size(), spawns.size() - 1));
  } else if (!camera) {
    if (kind != MeshKind::kBsp || spawns.empty())
      throw InputError(fmt::format("{}: a mesh needs a camera: give --camera "
                                   "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_y[,near]{}, or a JSON scene file",
                                   spec, kind == MeshKind::kBsp ? " (the map has no spawn points)" : ""));
    spawn = 0;
    camera_from = "no camera given, so ";
  }
  if (spawn >= 0) {
    const int index = spawn;
    const BspSpawnPoint& s = spawns[size_t(index)];
    camera = spawn_camera(s, resolution.x, resolution.y);
    camera_from += fmt::format("spawn {} of {} (entity {}, {} at {} yaw {} pitch {}), ", index,
                               spawns.size(), s.entity, s.classname, format_vec(s.origin),
                               s.yaw_degrees, s.pitch_degrees);
  }
  validate_camera(*camera, spec + ": camera");
  Scene scene = project(mesh, *camera, resolution.x, resolution.y, spec);
  const Camera& c = *camera;
  if (scene.triangles.empty())
    throw InputError(fmt::format(
        "{}: no triangle to draw: none of the mesh's {} triangles lies in front of the camera "
        "(eye {} target {} fov_y {} near {}); replay: --scene {} --camera {}",
        spec, mesh.triangles.size(), format_vec(c.eye), format_vec(c.target),
        c.fov_y_degrees, c.near_plane, spec, camera_option_text(c)));
  scene.description = fmt::format(
      "{}{}; {}x{}; {}camera eye {} target {} up {} fov_y {} near {}; default texture {}x{}; "
      "replay: --scene {} --camera {} --resolution {}x{}",
      scene_source, what, resolution.x, resolution.y, camera_from, format_vec(c.eye),
      format_vec(c.target), format_vec(c.up), c.fov_y_degrees, c.near_plane, texture.x, texture.y,
      spec, camera_option_text(c), resolution.x, resolution.y);
  return scene;
}

}  // namespace cdsim
