#include "scene.hpp"

#include "hard_cases.hpp"

#include "loaders/file_io.hpp"
#include "loaders/limits.hpp"
#include "loaders/scene_file.hpp"
#include "loaders/strict_text.hpp"

#include <fmt/format.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>
#include <string_view>

namespace cdsim {

namespace {

struct ClipVertex {
  glm::dvec4 position;  // clip space
  double u = 0, v = 0;  // texels
};

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, double t) {
  return {a.position + (b.position - a.position) * t, a.u + (b.u - a.u) * t, a.v + (b.v - a.v) * t};
}

// Sutherland-Hodgman against one plane; inside is distance >= 0. Attributes are
// affine in clip space, so interpolating them there is exact. The crossing is
// always computed from the inside end of the edge: two triangles that share
// an edge walk it in opposite directions, and the same operands in the same
// order give them the same crossing to the last bit, so the clipped shared
// edge stays shared (each pixel drawn once).
template <typename Distance>
std::vector<ClipVertex> clip(const std::vector<ClipVertex>& polygon, Distance distance) {
  std::vector<ClipVertex> out;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const ClipVertex& a = polygon[i];
    const ClipVertex& b = polygon[(i + 1) % polygon.size()];
    const double da = distance(a.position), db = distance(b.position);
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0))
      out.push_back(da >= 0 ? lerp(a, b, da / (da - db)) : lerp(b, a, db / (db - da)));
  }
  return out;
}

}  // namespace

Scene project(const Mesh& mesh, const Camera& camera, int width, int height,
              const std::string& name) {
  Scene scene;
  scene.name = name;
  scene.width = width;
  scene.height = height;
  const glm::dmat4 view = glm::lookAt(camera.eye, camera.target, camera.up);
  const glm::dmat4 projection = glm::perspective(glm::radians(camera.fov_y_degrees),
                                                 double(width) / double(height), camera.near_plane,
                                                 camera.near_plane * 1e6);
  const glm::dmat4 mvp = projection * view;
  const double near_w = camera.near_plane;
  for (size_t index = 0; index < mesh.triangles.size(); ++index) {
    const auto& tri = mesh.triangles[index];
    const glm::ivec2 size = mesh.texture_size[index];
    std::vector<ClipVertex> polygon;
    for (uint32_t vi : tri) {
      const MeshVertex& m = mesh.vertices.at(vi);
      polygon.push_back({mvp * glm::dvec4(m.position, 1.0), m.texcoord.x * size.x,
                         m.texcoord.y * size.y});
    }
    // For a perspective projection clip w is the eye depth, so the near plane is w = near.
    polygon = clip(polygon, [&](const glm::dvec4& p) { return p.w - near_w; });
    polygon = clip(polygon, [](const glm::dvec4& p) { return kGuardBand * p.w - p.x; });
    polygon = clip(polygon, [](const glm::dvec4& p) { return kGuardBand * p.w + p.x; });
    polygon = clip(polygon, [](const glm::dvec4& p) { return kGuardBand * p.w - p.y; });
    polygon = clip(polygon, [](const glm::dvec4& p) { return kGuardBand * p.w + p.y; });
    if (polygon.size() < 3) continue;
    std::vector<ScreenVertex> screen;
    for (const ClipVertex& c : polygon) {
      ScreenVertex s;
      s.x = (c.position.x / c.position.w + 1.0) * 0.5 * width;
      s.y = (1.0 - c.position.y / c.position.w) * 0.5 * height;
      s.w = c.position.w;
      s.u = c.u;
      s.v = c.v;
      screen.push_back(s);
    }
    for (size_t i = 1; i + 1 < screen.size(); ++i) {
      ScreenTriangle t;
      t.vertex = {screen[0], screen[i], screen[i + 1]};
      t.origin = fmt::format("mesh triangle {}", index);
      scene.triangles.push_back(t);
    }
  }
  return scene;
}

namespace {

// A rectangle from corner along edge_u and edge_v, cut into cells; each cell
// restarts its texture coordinates at 0 (repeat wrapping makes this invisible)
// so that |u| stays small on long walls.
void add_rectangle(Mesh& mesh, glm::dvec3 corner, glm::dvec3 edge_u, glm::dvec3 edge_v,
                   const std::vector<double>& cuts_u, int cells_v, double units_per_tile,
                   glm::ivec2 texture) {
  for (size_t i = 0; i + 1 < cuts_u.size(); ++i) {
    for (int j = 0; j < cells_v; ++j) {
      const double u0 = cuts_u[i], u1 = cuts_u[i + 1];
      const double v0 = double(j) / cells_v, v1 = double(j + 1) / cells_v;
      const double span_u = (u1 - u0) * glm::length(edge_u) / units_per_tile;
      const double span_v = (v1 - v0) * glm::length(edge_v) / units_per_tile;
      const auto base = static_cast<uint32_t>(mesh.vertices.size());
      const auto at = [&](double a, double b) { return corner + edge_u * a + edge_v * b; };
      mesh.vertices.push_back({at(u0, v0), {0, 0}});
      mesh.vertices.push_back({at(u1, v0), {span_u, 0}});
      mesh.vertices.push_back({at(u1, v1), {span_u, span_v}});
      mesh.vertices.push_back({at(u0, v1), {0, span_v}});
      mesh.triangles.push_back({base, base + 1, base + 2});
      mesh.triangles.push_back({base, base + 2, base + 3});
      mesh.texture_size.push_back(texture);
      mesh.texture_size.push_back(texture);
    }
  }
}

void add_box(Mesh& mesh, glm::dvec3 lo, glm::dvec3 hi, glm::ivec2 texture) {
  const glm::dvec3 d = hi - lo;
  const std::vector<double> whole = {0.0, 1.0};
  add_rectangle(mesh, lo, {d.x, 0, 0}, {0, d.y, 0}, whole, 1, 1.0, texture);
  add_rectangle(mesh, {lo.x, lo.y, hi.z}, {d.x, 0, 0}, {0, d.y, 0}, whole, 1, 1.0, texture);
  add_rectangle(mesh, lo, {0, 0, d.z}, {0, d.y, 0}, whole, 1, 1.0, texture);
  add_rectangle(mesh, {hi.x, lo.y, lo.z}, {0, 0, d.z}, {0, d.y, 0}, whole, 1, 1.0, texture);
  add_rectangle(mesh, {lo.x, hi.y, lo.z}, {d.x, 0, 0}, {0, 0, d.z}, whole, 1, 1.0, texture);
}

}  // namespace

Mesh default_mesh() {
  Mesh mesh;
  const double half_width = 4, height = 5, start = 3, end = -2000;
  // Cuts along the corridor: short near the camera, growing with distance, at
  // most 64 units so that texture coordinates stay far below 2^15 texels.
  std::vector<double> cuts = {0.0};
  for (double z = start, step = 1.0; z > end;) {
    z = std::max(end, z - step);
    cuts.push_back((start - z) / (start - end));
    step = std::min(64.0, step * 1.15);
  }
  const glm::dvec3 along{0, 0, end - start};
  const glm::ivec2 floor_texture{256, 256}, wall_texture{512, 512}, crate_texture{128, 128};
  add_rectangle(mesh, {-half_width, 0, start}, along, {2 * half_width, 0, 0}, cuts, 4, 2.0,
                floor_texture);
  add_rectangle(mesh, {-half_width, height, start}, along, {2 * half_width, 0, 0}, cuts, 2, 2.0,
                floor_texture);
  add_rectangle(mesh, {-half_width, 0, start}, along, {0, height, 0}, cuts, 2, 2.5, wall_texture);
  add_rectangle(mesh, {half_width, 0, start}, along, {0, height, 0}, cuts, 2, 2.5, wall_texture);
  add_rectangle(mesh, {-half_width, 0, end}, {2 * half_width, 0, 0}, {0, height, 0}, {0.0, 1.0}, 1,
                2.0, wall_texture);
  for (int i = 0; i < 12; ++i) {
    const double z = -4.0 - 9.0 * i;
    add_box(mesh, {-half_width, 0, z - 0.4}, {-half_width + 0.6, height, z + 0.4}, wall_texture);
    add_box(mesh, {half_width - 0.6, 0, z - 0.4}, {half_width, height, z + 0.4}, wall_texture);
  }
  for (int i = 0; i < 6; ++i) {
    const double x = (i % 2 == 0 ? -1.5 : 1.8) + 0.3 * i;
    const double z = -6.0 - 13.0 * i;
    add_box(mesh, {x, 0, z}, {x + 1.0, 1.0, z + 1.0}, crate_texture);
  }
  return mesh;
}

Camera default_camera() {
  Camera camera;
  camera.eye = {0.4, 1.7, 0.0};
  camera.target = {1.2, 1.1, -12.0};
  const double roll = glm::radians(20.0);
  camera.up = {std::sin(roll), std::cos(roll), 0.0};
  camera.fov_y_degrees = 70.0;
  camera.near_plane = 0.05;
  return camera;
}

Scene default_scene() {
  const Camera c = default_camera();
  Scene scene = project(default_mesh(), c, 1920, 1080, "default");
  scene.description = fmt::format(
      "embedded corridor, {}x{}, eye ({}, {}, {}) target ({}, {}, {}) up ({:.4f}, {:.4f}, {}) "
      "fov_y {} near {}",
      scene.width, scene.height, c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z,
      c.up.x, c.up.y, c.up.z, c.fov_y_degrees, c.near_plane);
  return scene;
}

Scene dense_scene() {
  constexpr int kRings = 128, kSegments = 256;
  constexpr double kPi = 3.14159265358979323846;
  Mesh mesh;
  // Vertices ring by ring from pole to pole; the seam repeats its column so
  // that s runs from 0 to 4 tiles without wrapping.
  for (int i = 0; i <= kRings; ++i) {
    const double theta = kPi * i / kRings;
    for (int j = 0; j <= kSegments; ++j) {
      const double phi = 2 * kPi * j / kSegments;
      mesh.vertices.push_back({{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)},
                               {4.0 * j / kSegments, 2.0 * i / kRings}});
    }
  }
  const auto at = [](int i, int j) { return static_cast<uint32_t>(i * (kSegments + 1) + j); };
  for (int i = 0; i < kRings; ++i)
    for (int j = 0; j < kSegments; ++j) {
      // The ring at a pole is one point: one triangle per segment there.
      if (i != 0) mesh.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      if (i != kRings - 1) mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  mesh.texture_size.assign(mesh.triangles.size(), glm::ivec2{512, 512});
  Camera camera;
  camera.eye = {0.3, 0.4, 3.2};
  camera.target = {0, 0, 0};
  camera.fov_y_degrees = 50;
  Scene scene = project(mesh, camera, 1280, 720, "dense");
  scene.description = fmt::format(
      "embedded UV sphere, {} rings x {} segments ({} triangles), 1280x720, eye ({}, {}, {}) "
      "target (0, 0, 0) fov_y {}",
      kRings, kSegments, mesh.triangles.size(), camera.eye.x, camera.eye.y, camera.eye.z,
      camera.fov_y_degrees);
  return scene;
}

Scene load_triangle_file(const std::string& path) {
  const std::vector<uint8_t> bytes = read_file_bytes(path);
  return load_triangle_text(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                            path);
}

Scene load_triangle_stream(std::istream& in, const std::string& path) {
  return load_triangle_text(read_stream_text(in, path), path);
}

Scene load_triangle_text(std::string_view text, const std::string& path) {
  Scene scene;
  scene.name = path;
  scene.description = "triangle list " + path;
  scene.width = 1920;
  scene.height = 1080;
  text = without_utf8_bom(text);
  int number = 0;
  std::vector<std::string_view> words;
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++number;
    const auto fail = [&](const std::string& what) {
      throw InputError(fmt::format("{}:{}: {}", path, number, what));
    };
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    words.clear();
    for_each_word(line, [&](std::string_view word) { words.push_back(word); });
    if (words.empty()) continue;
    if (words[0] == "resolution") {
      if (words.size() != 3) fail("expected 'resolution W H'");
      long long size[2] = {0, 0};
      for (size_t i = 0; i < 2; ++i) {
        const std::optional<long long> value = parse_integer(words[i + 1]);
        if (!value)
          fail(fmt::format("resolution {} is not an integer (expected 'resolution W H')",
                           quote_bytes(words[i + 1])));
        size[i] = *value;
      }
      if (size[0] < 1 || size[1] < 1 || size[0] > limits::kMaxResolution ||
          size[1] > limits::kMaxResolution)
        fail(fmt::format("resolution {}x{} is outside 1..{}", size[0], size[1], limits::kMaxResolution));
      scene.width = static_cast<int>(size[0]);
      scene.height = static_cast<int>(size[1]);
      continue;
    }
    std::array<double, 15> numbers{};
    for (size_t k = 0; k < words.size(); ++k) {
      const ParsedNumber parsed = parse_number(words[k]);
      if (parsed.problem == NumberProblem::kNotANumber) fail(number_problem(parsed, words[k]));
      if (!parsed.ok()) {
        // Named by vertex and field; the unit's own check (to_unit) would
        // name the triangle but could not show the text.
        if (k >= 15) fail(number_problem(parsed, words[k]));
        const std::string field = fmt::format("{} = {}", "xywuv"[k % 5], quote_bytes(words[k]));
        if (parsed.problem == NumberProblem::kNotFinite)
          fail(fmt::format("vertex {} has a non-finite value: {}", k / 5, field));
        fail(fmt::format("vertex {} has a value out of range: {} (its magnitude exceeds {:g})", k / 5,
                         field, parsed.limit));
      }
      if (k < 15) numbers[k] = parsed.value;
    }
    if (words.size() != 15)
      fail(fmt::format("expected 15 numbers (x y w u v for 3 vertices), found {}", words.size()));
    if (scene.triangles.size() >= limits::kMaxTriangles)
      fail(fmt::format("more than {} triangles, the cap on one triangle list", limits::kMaxTriangles));
    ScreenTriangle t;
    for (size_t i = 0; i < 3; ++i)
      t.vertex[i] = {numbers[5 * i], numbers[5 * i + 1], numbers[5 * i + 2], numbers[5 * i + 3],
                     numbers[5 * i + 4]};
    t.origin = fmt::format("{}:{}", path, number);
    scene.triangles.push_back(t);
  }
  return scene;
}

Scene load_scene(const std::string& spec, const SceneOptions& options) {
  if (is_hard_case(spec)) {
    if (!options.empty())
      throw InputError(fmt::format("{}: --camera, --spawn and --resolution do not apply to a hard case", spec));
    return hard_case_scene(spec);
  }
  if (spec.empty() || spec == "default") {
    if (options.empty()) return default_scene();
    return load_scene_file("default", options);
  }
  if (spec == "dense") {
    if (!options.empty())
      throw InputError("dense: --camera, --spawn and --resolution do not apply to the embedded dense scene");
    return dense_scene();
  }
  if (is_scene_file(spec)) return load_scene_file(spec, options);
  if (!options.empty())
    throw InputError(fmt::format("{}: --camera, --spawn and --resolution do not apply to a "
                                 "screen-space triangle list",
                                 spec));
  Scene scene = load_triangle_file(spec);
  if (scene.triangles.empty())
    throw InputError(fmt::format("{}: no triangle to draw: the file has no triangle lines", spec));
  return scene;
}

Scene load_scene(const std::string& spec) { return load_scene(spec, SceneOptions{}); }

}  // namespace cdsim
