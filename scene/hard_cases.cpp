#include "hard_cases.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace cdsim {

namespace {

constexpr const char* kPrefix = "hard:";

struct Builder {
  Scene scene;
  Builder(const std::string& name, int width, int height, const std::string& description) {
    scene.name = std::string(kPrefix) + name;
    scene.width = width;
    scene.height = height;
    scene.description = description;
  }
  // Vertices as {x, y, w, u, v}.
  void add(std::array<double, 5> a, std::array<double, 5> b, std::array<double, 5> c) {
    ScreenTriangle t;
    size_t i = 0;
    for (const auto& v : {a, b, c}) t.vertex[i++] = {v[0], v[1], v[2], v[3], v[4]};
    t.origin = fmt::format("{} #{}", scene.name, scene.triangles.size());
    scene.triangles.push_back(t);
  }
  // A vertex whose 1/w is exactly q (a binary32 number).
  static std::array<double, 5> at_q(double x, double y, double q, double u, double v) {
    return {x, y, 1.0 / q, u, v};
  }
};

Scene parallel() {
  Builder b("parallel", 512, 512, "triangles parallel to the screen: equal w, u and v on the 1/256 grid");
  b.add({3.2, 4.7, 7, 10, 20}, {310.4, 40.1, 7, 900.5, 61.25}, {50.3, 250.9, 7, -300.75, 812});
  b.add({500, 500, 0.25, 0, 0}, {20, 480, 0.25, 4000, 0}, {490, 30, 0.25, 0, 4000});
  b.add({100, 300, 50, 3, 3}, {110, 500, 50, 3, 83}, {104, 310, 50, 9, 5});
  return b.scene;
}

Scene slope_one() {
  // q = 1 at (10, 10); q at the x and y neighbours 64 pixels away makes
  // q_x / q_y = -(1 - 2^-16), -1, -(1 + 2^-16) (g = -q_x/q_y, g_frac 16), and
  // the same with q falling along y (g = +1 and one LSB either side). All q are
  // exact binary32 numbers.
  Builder b("slope-one", 512, 512,
            "|g| = 1 exactly and one LSB (g_frac 16) either side, both signs");
  const double lsb = std::ldexp(1.0, -17);
  int k = 0;
  for (const double sign : {1.0, -1.0})
    for (const double delta : {-lsb, 0.0, lsb}) {
      const double x0 = 10 + 80 * (k % 3), y0 = 10 + 160 * (k / 3);
      ++k;
      b.add(Builder::at_q(x0, y0, 1.0, 0, 0), Builder::at_q(x0 + 64, y0, 1.5 + delta, 256, 0),
            Builder::at_q(x0, y0 + 64, 1.0 + sign * 0.5, 0, 256));
    }
  return b.scene;
}

Scene edge_on() {
  // Strips from w = 0.1 to w = 1000 (far/near depth ratio 10^4), floor-like
  // (q changes along y) and wall-like (along x), at several slants.
  Builder b("edge-on", 1024, 1024, "near edge-on triangles, far/near depth ratio 10^4");
  b.add({40, 1000, 0.1, 0, 0}, {980, 1010, 0.1, 64, 0}, {520, 500, 1000, 32, 4096});
  b.add({60, 990, 0.1, 0, 0}, {500, 498, 1000, 4096, 64}, {40, 600, 0.3, 0, 64});
  b.add({1000, 40, 0.1, 0, 0}, {1010, 980, 0.1, 0, 64}, {500, 520, 1000, 4096, 32});
  b.add({20, 20, 0.1, 0, 0}, {500, 500, 1000, 2000, 2000}, {20, 300, 0.1, 0, 40});
  return b.scene;
}

Scene near_plane() {
  // Through the front end: one vertex exactly on the near plane, and a triangle
  // straddling it (one vertex behind the eye), both clipped homogeneously.
  Camera camera;
  camera.eye = {0, 1, 0};
  camera.target = {0, 0.8, -10};
  camera.up = {0, 1, 0};
  camera.fov_y_degrees = 60;
  camera.near_plane = 0.05;
  Mesh mesh;
  // The eye looks slightly down; a point straight ahead at depth `near` along
  // the view direction lies exactly on the near plane.
  const glm::dvec3 forward = glm::normalize(camera.target - camera.eye);
  const glm::dvec3 on_near = camera.eye + forward * camera.near_plane;
  mesh.vertices = {{on_near, {0, 0}}, {{-2, 0, -5}, {4, 0}}, {{2, 0, -5}, {4, 4}},
                   {{-0.02, 1.0, 0.5}, {0, 0}}, {{0.02, 1.0, 0.5}, {2, 0}}, {{0, 0.9, -6}, {1, 6}}};
  mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
  mesh.texture_size = {{256, 256}, {256, 256}};
  Scene s = project(mesh, camera, 640, 480, std::string(kPrefix) + "near-plane");
  s.description = "a vertex on the near plane and a triangle straddling it, clipped by the front end";
  return s;
}

Scene grazing() {
  // A floor strip 1 unit wide and 3000 long, seen from 1 unit above it at a
  // grazing angle by a camera rolled by about 3 degrees, at 1080p: its far end
  // lies a few pixels from the horizon, and the horizon, so the lines of
  // constant depth, runs across the pixel grid (g != 0). Generic geometry for
  // the near-horizon triangles of real maps (issue 41).
  Camera camera;
  camera.eye = {0, 1, 2};
  camera.target = {0, 0.999, -10};
  camera.up = {0.05, 1, 0};
  camera.fov_y_degrees = 60;
  Mesh mesh;
  mesh.vertices = {{{-0.5, 0, 0}, {0, 0}}, {{0.5, 0, 0}, {0.05, 0}}, {{0.5, 0, -3000}, {0.05, 100}},
                   {{-0.5, 0, -3000}, {0, 100}}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.texture_size = {{256, 256}, {256, 256}};
  Scene s = project(mesh, camera, 1920, 1080, std::string(kPrefix) + "grazing");
  s.description = "a floor strip at a grazing angle reaching a few pixels from its horizon, camera rolled, 1920 x 1080";
  return s;
}

Scene horizon() {
  // Small triangles whose far vertex lies 0.05 to 1.8 line gaps from the
  // horizon (q = 0) of their plane: nearly edge-on, as the flagged triangles
  // of the OpenArena maps are (docs/robustness.md, "Flagged triangles").
  // q = a (y - y_h - t (x - x_f)) with the horizon at y_h + t (x - x_f): the
  // lines of constant depth run at slope t across the pixel grid. Heights from
  // a fiftieth of a pixel to 1.5 pixels; every fourth one transposed (y-major).
  Builder b("horizon", 512, 512, "small near-edge-on triangles 0.05 to 1.8 line gaps from their horizon");
  const double gaps[] = {0.05, 0.12, 0.25, 0.5, 0.67, 0.9, 1.2, 1.8};
  const double heights[] = {0.02, 0.3, 1.5};
  const double tilts[] = {0.03, -0.11};
  int n = 0;
  for (const double gap : gaps)
    for (const double height : heights)
      for (const double tilt : tilts) {
        const double x0 = 20 + 60 * (n % 8), y0 = 21.1 + 60 * (n / 8);
        // The far vertex 0.6 pixels below a row of pixel centres, the others below it.
        const std::array<std::array<double, 2>, 3> at = {{{x0 + 3.3, y0}, {x0, y0 + height}, {x0 + 7.1, y0 + height}}};
        double horizon = 1e300;  // y_h: the least of y - t (x - x_f) over the vertices, less the gap
        for (const auto& p : at) horizon = std::min(horizon, p[1] - tilt * (p[0] - at[0][0]));
        horizon -= gap;
        std::array<std::array<double, 5>, 3> v{};
        const double u[] = {0, 37.5, 81.25}, vv[] = {0, 512, 130};
        for (size_t i = 0; i < 3; ++i) {
          const double q = 0.01 * (at[i][1] - horizon - tilt * (at[i][0] - at[0][0]));
          v[i] = {at[i][0], at[i][1], 1.0 / q, u[i] + 7 * n, vv[i]};
          if (n % 4 == 3) std::swap(v[i][0], v[i][1]);
        }
        b.add(v[0], v[1], v[2]);
        ++n;
      }
  return b.scene;
}

Scene sliver() {
  Builder b("sliver", 4096, 4096, "slivers under a pixel wide and thousands of pixels long");
  b.add({10, 10, 1, 0, 0}, {4000, 3000, 8, 3000, 300}, {10.3, 10.2, 1, 0, 1});
  b.add({100, 5, 1, 0, 0}, {100.4, 5, 1, 1, 0}, {100.2, 4050, 20, 0, 2000});
  b.add({5, 2000.1, 2, 0, 0}, {4090, 2000.3, 2, 4000, 0}, {5, 2000.5, 2, 0, 1});
  b.add({4000, 100, 10, 0, 0}, {50, 3900, 0.5, 2000, 2000}, {4000.5, 100.1, 10, 1, 0});
  return b.scene;
}

Scene subpixel() {
  // Seeded, so the scene is the same everywhere (seed 9001).
  Builder b("subpixel", 64, 64, "sub-pixel and zero-area triangles (seed 9001)");
  std::mt19937_64 rng(9001);
  std::uniform_real_distribution<double> pos(1, 63), size(-0.6, 0.6), w(0.5, 5);
  for (int i = 0; i < 60; ++i) {
    const double x = pos(rng), y = pos(rng);
    b.add({x, y, w(rng), 0, 0}, {x + size(rng), y + size(rng), w(rng), 1, 0},
          {x + size(rng), y + size(rng), w(rng), 0, 1});
  }
  b.add({5, 5, 1, 0, 0}, {20, 20, 2, 1, 1}, {35, 35, 3, 2, 2});  // collinear
  b.add({9, 9, 1, 0, 0}, {9, 9, 1, 0, 0}, {30, 12, 1, 4, 0});    // repeated vertex
  b.add({7.5, 7.5, 1, 0, 0}, {7.5, 7.5, 2, 1, 0}, {7.5, 7.5, 3, 0, 1});  // a point on a centre
  return b.scene;
}

Scene watertight() {
  // A 16 x 16 grid over 128 x 128 pixels whose vertices sit on pixel centres,
  // with w varying smoothly, cut into triangles with alternating diagonals and
  // windings, plus a fan of 12 triangles around the centre (64.5, 64.5).
  Builder b("watertight", 160, 160, "vertices on pixel centres and shared edges: a grid and a fan");
  const auto vertex = [](double x, double y) {
    return std::array<double, 5>{x, y, 1.0 + 0.02 * x + 0.01 * y, 4 * x, 4 * y};
  };
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const double x0 = 8 * i + 0.5, y0 = 8 * j + 0.5, x1 = x0 + 8, y1 = y0 + 8;
      if ((i + j) % 2) {
        b.add(vertex(x0, y0), vertex(x1, y0), vertex(x1, y1));
        b.add(vertex(x0, y0), vertex(x0, y1), vertex(x1, y1));  // other winding
      } else {
        b.add(vertex(x0, y0), vertex(x1, y0), vertex(x0, y1));
        b.add(vertex(x1, y0), vertex(x1, y1), vertex(x0, y1));
      }
    }
  return b.scene;
}

Scene viewport_8k() {
  Builder b("viewport-8k", 8192, 8192, "8192 x 8192 viewport, triangles reaching past every edge");
  b.add({-3000, -2500, 1, 0, 0}, {700, -10, 3, 1000, 0}, {-5, 600, 2, 0, 1000});
  b.add({8100, -900, 2, 0, 0}, {11000, 400, 6, 2000, 0}, {8000, 500, 1, 0, 500});
  b.add({-100, 8000, 1, 0, 0}, {600, 8300, 4, 500, 0}, {-2000, 12000, 9, 0, 900});
  b.add({7600, 7700, 1, 0, 0}, {12000, 8100, 1.5, 800, 0}, {8150, 14000, 2, 0, 800});
  b.add({3000, 4000, 1, 0, 0}, {5000, 4100, 30, 3000, 0}, {4000, 4800, 5, 0, 2000});
  return b.scene;
}

Scene texcoord_range() {
  Builder b("texcoord-range", 512, 512,
            "texture coordinates near +-2^15 texels, and a 16384-texel texture on 40 pixels");
  b.add({10, 10, 1, 32000, -32700}, {200, 20, 2, 32700, -32700}, {30, 220, 1.5, 32000, -32000});
  b.add({300, 300, 1, -32700, 32000}, {500, 310, 1, -32000, 32000}, {310, 500, 1, -32700, 32700});
  b.add({250, 40, 1, 0, 0}, {290, 42, 3, 16383, 0}, {255, 80, 2, 0, 16383});
  return b.scene;
}

Scene table_overflow() {
  Builder b("table-overflow", 2048, 2048,
            "triangles needing more lines than the default table (1024 lines) holds");
  // Tall and narrow, so that they need 1900 lines but few pixels.
  // 1/w changes along y, so the lines run across and a triangle needs one per row.
  b.add({20, 10, 1, 0, 0}, {180, 10, 1, 2000, 0}, {60, 2030, 4, 0, 3000});
  b.add({1900, 30, 5, 0, 0}, {2030, 30, 5, 500, 0}, {1990, 2030, 1, 0, 4000});
  return b.scene;
}

Scene half_tie() {
  // q_x / q_y = -1/2 exactly, so g = 1/2 and g o lands exactly on .5 in every
  // odd column; plus g = -1/2.
  Builder b("half-tie", 256, 256, "g o exactly on .5: g = +-1/2");
  b.add(Builder::at_q(10, 10, 1.0, 0, 0), Builder::at_q(74, 10, 1.25, 256, 0),
        Builder::at_q(10, 74, 1.5, 0, 256));
  b.add(Builder::at_q(110, 10, 1.0, 0, 0), Builder::at_q(174, 10, 0.75, 256, 0),
        Builder::at_q(110, 74, 1.5, 0, 256));
  b.add(Builder::at_q(10, 110, 1.0, 0, 0), Builder::at_q(202, 110, 1.75, 768, 0),
        Builder::at_q(10, 238, 2.0, 0, 512));
  return b.scene;
}

Scene bad_input() {
  Builder b("bad-input", 64, 64, "NaN, infinity and w <= 0 at the unit: refused before the unit");
  b.add({1, 1, 1, 0, 0}, {20, 2, std::nan(""), 0, 0}, {3, 30, 1, 0, 0});
  b.add({1, 1, 1, 0, 0}, {20, 2, 1, 0, 0}, {HUGE_VAL, 30, 1, 0, 0});
  b.add({1, 1, 1, 0, 0}, {20, 2, -0.5, 0, 0}, {3, 30, 1, 0, 0});
  b.add({1, 1, 0.0, 0, 0}, {20, 2, 1, 0, 0}, {3, 30, 1, 0, 0});
  return b.scene;
}

struct Entry {
  HardCase info;
  Scene (*make)();
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> list = {
      {{"parallel", "every design but affine within one output LSB (Kim-style: plus 2^-kim_frac); affine too, w being constant"}, parallel},
      {{"slope-one", "orientation and g as built (x-major g = -65535 and -65536, y-major g' = -65535; mirrored positive); coverage exact; cd-linear footprint error < 0.05"}, slope_one},
      {{"edge-on", "divide within 1e-2 of the footprint; cd-none within one footprint (half a pixel off its line where the footprint itself changes fast); cd-linear better than cd-none on mean and footprint max"}, edge_on},
      {{"near-plane", "front end clips at w = near: every vertex has w >= near; pixels drawn; divide within 2 output LSBs plus input quantisation"}, near_plane},
      {{"grazing", "divide, cd-persp and the designs with a divide fallback (cd-linear-div, cd-persp-div: both triangles go to divide) within 1e-2 of the footprint; cd-linear is not (0.11 footprints: linear correction errs by about 1/(4 d) footprints d line gaps from a horizon), nor cd-none (0.53, half a line gap anywhere) or adaptive (1,630, its depth limit); none flagged (docs/robustness.md)"}, grazing},
      {{"horizon", "no constant-depth design uses a line past the horizon (no depth_range, no neighbour_dropped): the line phase keeps them on the near side, where line_phase_bits=0 drops and flags corrections; divide within 1e-2 footprints; cd-persp at the widest widths within 2^-8 with no flag (at default widths eps_int=2 saturates, flagged); cd-none (4.1 footprints) and cd-linear (2.2) are not bounded a line gap from a horizon (docs/robustness.md)"}, horizon},
      {{"sliver", "coverage exact against a brute-force test; walker cycles include every column of the box"}, sliver},
      {{"subpixel", "zero-area triangles emit nothing and cost setup cycles only; sub-pixel ones cover at most a few pixels, exactly"}, subpixel},
      {{"watertight", "every pixel under the grid covered exactly once, in every design"}, watertight},
      {{"viewport-8k", "fragments only inside the 8192 x 8192 viewport, exactly the covered ones; constant-depth designs walk tall triangles in bands"}, viewport_8k},
      {{"texcoord-range", "no output saturation for coordinates inside +-2^15 in divide and Kim-style designs; any saturation is flagged"}, texcoord_range},
      {{"table-overflow", "constant-depth designs flag banding and give the same fragments as a table deep enough"}, table_overflow},
      {{"half-tie", "g = +-1/2 exactly, ties resolved toward +inf (t = +1/2); coverage exact; cd-linear within 0.05 footprints"}, half_tie},
      {{"bad-input", "refused before the unit with a message naming the triangle and vertex (NaN, infinity, w <= 0)"}, bad_input},
  };
  return list;
}

}  // namespace

const std::vector<HardCase>& hard_cases() {
  static const std::vector<HardCase> list = [] {
    std::vector<HardCase> out;
    for (const Entry& e : entries()) out.push_back(e.info);
    return out;
  }();
  return list;
}

bool is_hard_case(const std::string& spec) { return spec.rfind(kPrefix, 0) == 0; }

Scene hard_case_scene(const std::string& spec) {
  const std::string name = spec.substr(std::string(kPrefix).size());
  if (name == "all") {
    // Every case but bad-input, at their own screen positions in the largest viewport.
    Scene all;
    all.name = spec;
    all.description = "every hard case but bad-input, in one 8192 x 8192 scene";
    all.width = all.height = 0;
    for (const Entry& e : entries()) {
      if (e.info.name == "bad-input") continue;
      const Scene s = e.make();
      all.width = std::max(all.width, s.width);
      all.height = std::max(all.height, s.height);
      all.triangles.insert(all.triangles.end(), s.triangles.begin(), s.triangles.end());
    }
    return all;
  }
  for (const Entry& e : entries())
    if (e.info.name == name) return e.make();
  std::string known;
  for (const Entry& e : entries()) known += " " + e.info.name;
  throw InputError(fmt::format("unknown hard case '{}'; known: all{}", name, known));
}

}  // namespace cdsim
