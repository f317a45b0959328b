// gl_oracle: renders a cdsim scene with Mesa's llvmpipe (EGL surfaceless, an
// RGBA32F colour buffer, a fragment shader writing the perspective-correct
// (u, v)) and compares every pixel with cdsim's coverage (covers()) and exact
// reference (ExactReference::at_pixel). See docs/oracle.md.
//
// Exit status: 0 when every figure is within its documented tolerance, 1 when
// not, 2 for bad input or usage, 77 when no llvmpipe context can be created
// (ctest's SKIP_RETURN_CODE).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "pixel_coverage.hpp"
#include "evaluate.hpp"
#include "exact.hpp"
#include "gl_render.hpp"
#include "scene.hpp"
#include "scene_cli.hpp"
#include "triangle.hpp"
#include "widths.hpp"

namespace {

using namespace cdsim;
using gl_oracle::GlRenderer;
using gl_oracle::GlVertex;
using gl_oracle::Texel;

constexpr int kSkip = 77;
constexpr int64_t kMargin = 8;  // pixels around a batch's regions that are also checked
constexpr long double kEps = 0x1p-24L;  // binary32 unit roundoff

struct Options {
  std::string scene = "default";
  SceneOptions scene_options;  // --camera, --spawn, --resolution as cdsim takes them
  int tile = 2048;
  int show = 10;
  double k = 16;           // constant of the u, v bound (docs/oracle.md)
  bool y_up = false;       // experiment: map cdsim rows to GL window rows bottom-up
  bool clip_upper_left = false;  // experiment: glClipControl(GL_UPPER_LEFT)
};

struct RowSpan {
  int64_t y, lo, hi;  // pixels lo..hi of row y
};

// Everything the comparison needs about one scene triangle.
struct Tri {
  EdgeSet edges;
  PixelBox box;            // snapped extent +- 1 pixel, in the viewport
  // The pixels compared for this triangle: every pixel whose centre lies within
  // one pixel (in x and in y) of the snapped triangle, one span per row.
  std::vector<RowSpan> region;
  int64_t cx = 0, cy = 0;  // integer centre of the triangle's snapped extent (scene pixels)
  long double extent = 0;  // longer side of the snapped extent, pixels
  long double max_u = 0, max_v = 0;  // largest |u|, |v| at the vertices
  std::array<long double, 3> q{};    // 1/w per vertex
  long double q_max = 0, max_uq = 0, max_vq = 0;  // largest q, |u q|, |v q| at the vertices
  long double shape = 0;  // extent * perimeter / (2 area): how ill-conditioned the plane setup is
  bool gl_clipped = false;  // a vertex lies outside the GL viewport: GL clips it
};

struct Difference {
  int64_t triangle, x, y;
  bool gl_covers;
  std::string why;
};

struct Stats {
  int64_t region_pixels = 0;   // (triangle, pixel) pairs examined
  int64_t on_edge = 0;         // of those, (pixel, edge) pairs with the centre exactly on the edge
  int64_t pixels_read = 0;     // pixels cleared and read back from GL
  int64_t both = 0;            // covered by both: u, v compared
  int64_t gl_only = 0, cdsim_only = 0, stray = 0, unexpected = 0;
  std::map<std::string, int64_t> categories;
  std::vector<Difference> shown;
  std::vector<float> du, dv;
  double max_du = 0, max_dv = 0, max_ratio = 0, max_normalised = 0;
  struct Worst {
    int64_t triangle = -1, x = 0, y = 0;
    double gl_u = 0, gl_v = 0, exact_u = 0, exact_v = 0, bound_u = 0, bound_v = 0, ratio = 0;
    double rho = 0, g = 0, length = 0;
  } worst, largest;
  int64_t over_bound = 0;
};

long double edge_value(const EdgeSet& e, size_t i, int64_t x, int64_t y) {
  return static_cast<long double>(e.a[i] * pixel_centre(x, e.subpixel_bits) +
                                  e.b[i] * pixel_centre(y, e.subpixel_bits) + e.c[i]);
}

// Why GL and cdsim disagree at a pixel, and whether that is expected. A
// centre exactly on an edge is the fill rule's business: expected only for a
// top or bottom edge when the configuration turns llvmpipe's horizontal rule
// around (--y-up xor --clip-upper-left). A centre within 1/512 px of an edge is
// expected only if the float position check allowed misrounding; a triangle GL
// had to clip gets new float vertices. Anything else is unexplained.
struct Explanation {
  std::string why;
  bool expected = false;
};

Explanation explain(const Tri& t, int64_t x, int64_t y, bool horizontal_rule_flipped,
                    bool positions_exact) {
  const EdgeSet& e = t.edges;
  if (e.det == 0) return {"zero-area triangle (unexplained)", false};
  if (t.gl_clipped) return {"GL clipped the triangle at its viewport (new vertices in float)", true};
  std::string on;
  bool horizontal = false;
  long double nearest = 1e30L;
  for (size_t i = 0; i < 3; ++i) {
    const long double value = edge_value(e, i, x, y);
    const long double length = std::hypot(static_cast<long double>(e.a[i]),
                                          static_cast<long double>(e.b[i]));
    if (value == 0) {
      const char* kind = e.a[i] == 0 ? (e.b[i] > 0 ? "top" : "bottom")
                                     : (e.a[i] > 0 ? "left" : "right");
      horizontal = horizontal || e.a[i] == 0;
      if (!on.empty()) on += "+";
      on += kind;
    }
    if (length > 0) nearest = std::min(nearest, std::fabs(value) / length);
  }
  if (!on.empty()) {
    const bool expected = horizontal_rule_flipped && horizontal;
    return {"centre exactly on a " + on + " edge (fill rule" +
                (expected ? ", GL's horizontal rule turned around)" : ": unexplained)"),
            expected};
  }
  const long double pixels = nearest / std::ldexp(1.0L, e.subpixel_bits);
  if (pixels < 1.0L / 512)
    return {std::string("centre within 1/512 px of an edge (position precision") +
                (positions_exact ? ": unexplained, positions are exact)" : ")"),
            !positions_exact};
  return {"unexplained", false};
}

// The position GL's float pipeline reaches for one snapped coordinate, in
// subpixel units after llvmpipe's snap (round to nearest even of 256*(x - 0.5)),
// relative to the exact value. Two ways of dividing by w are tried: x/w and
// x*(1/w). Returns the larger distance, in subpixel units, before rounding.
double float_path_error(double offset_from_centre, float w, int half_size, double centre_window) {
  const float ndc = static_cast<float>(offset_from_centre / half_size);  // exact
  const float clip = ndc * w;
  const float ndc_a = clip / w;
  const float ndc_b = clip * (1.0f / w);
  double worst = 0;
  for (float n : {ndc_a, ndc_b}) {
    // Scale by a power of two (exact), add the integer viewport centre (rounded).
    const float window = n * static_cast<float>(half_size) + static_cast<float>(centre_window);
    const float snapped_input = (window - 0.5f) * 256.0f;
    const double exact = (offset_from_centre + centre_window - 0.5) * 256.0;
    worst = std::max(worst, std::fabs(static_cast<double>(snapped_input) - exact));
  }
  return worst;
}

int run(const Options& options) {
  const auto started = std::chrono::steady_clock::now();
  Widths widths;  // the unit's defaults: 16.8 snapping, as llvmpipe (FIXED_ORDER 8)
  PreparedScene prepared;
  try {
    prepared = prepare(load_scene(options.scene, options.scene_options), widths);
  } catch (const std::exception& e) {
    std::cerr << "gl_oracle: " << e.what() << '\n';
    return 2;
  }
  const Scene& scene = prepared.scene;
  const int sub = widths.subpixel_bits;
  if (sub != 8) {
    std::cerr << "gl_oracle: llvmpipe snaps to 8 subpixel bits; subpixel_bits is " << sub << '\n';
    return 2;
  }
  const int64_t n = static_cast<int64_t>(scene.triangles.size());
  if (n >= (int64_t{1} << 24)) {
    std::cerr << "gl_oracle: more than 2^24 triangles: ids would not be exact in binary32\n";
    return 2;
  }
  const int tile_w = std::min(scene.width, options.tile);
  const int tile_h = std::min(scene.height, options.tile);

  std::unique_ptr<GlRenderer> gl;
  try {
    gl = std::make_unique<GlRenderer>(tile_w, tile_h, options.clip_upper_left);
  } catch (const gl_oracle::Unavailable& e) {
    std::cout << "gl_oracle: SKIPPED: no EGL surfaceless llvmpipe context: " << e.what() << '\n';
    return kSkip;
  }
  const int size = [&] {  // the largest power-of-two viewport GL allows
    int s = 1;
    while (s * 2 <= gl->limits().max_dim) s *= 2;
    return s;
  }();
  const int half = size / 2;

  // Per-triangle data and the vertices GL draws.
  std::vector<Tri> tris(static_cast<size_t>(n));
  std::vector<ExactReference> exact;
  exact.reserve(static_cast<size_t>(n));
  std::vector<GlVertex> vertices(static_cast<size_t>(3 * n));
  double worst_position_error = 0;  // subpixel units, before llvmpipe's rounding
  int64_t clipped = 0;
  for (int64_t t = 0; t < n; ++t) {
    const ScreenTriangle& screen = scene.triangles[static_cast<size_t>(t)];
    const UnitTriangle& unit = prepared.unit[static_cast<size_t>(t)];
    exact.emplace_back(screen, unit, sub);
    Tri& tri = tris[static_cast<size_t>(t)];
    tri.edges = exact.back().edges();
    int64_t x_lo = INT64_MAX, x_hi = INT64_MIN, y_lo = INT64_MAX, y_hi = INT64_MIN;
    for (const auto& v : unit.vertex) {
      x_lo = std::min(x_lo, v.x), x_hi = std::max(x_hi, v.x);
      y_lo = std::min(y_lo, v.y), y_hi = std::max(y_hi, v.y);
    }
    const int64_t one = int64_t{1} << sub;
    tri.box.x_lo = std::max<int64_t>(0, (x_lo >> sub) - 1);
    tri.box.x_hi = std::min<int64_t>(scene.width - 1, (x_hi >> sub) + 1);
    tri.box.y_lo = std::max<int64_t>(0, (y_lo >> sub) - 1);
    tri.box.y_hi = std::min<int64_t>(scene.height - 1, (y_hi >> sub) + 1);
    {
      std::array<double, 3> vx{}, vy{};
      for (size_t i = 0; i < 3; ++i) {
        vx[i] = snapped_pixels(unit.vertex[i].x, sub);
        vy[i] = snapped_pixels(unit.vertex[i].y, sub);
      }
      for (int64_t row = tri.box.y_lo; row <= tri.box.y_hi; ++row) {
        // The triangle's x-range within 1 px of the row's centre line.
        const double y0 = static_cast<double>(row) - 0.5, y1 = static_cast<double>(row) + 1.5;
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < 3; ++i) {
          if (vy[i] >= y0 && vy[i] <= y1) lo = std::min(lo, vx[i]), hi = std::max(hi, vx[i]);
          const size_t j = (i + 1) % 3;
          if (vy[i] == vy[j]) continue;
          for (double yb : {y0, y1}) {
            if (yb < std::min(vy[i], vy[j]) || yb > std::max(vy[i], vy[j])) continue;
            const double x = vx[i] + (vx[j] - vx[i]) * (yb - vy[i]) / (vy[j] - vy[i]);
            lo = std::min(lo, x), hi = std::max(hi, x);
          }
        }
        if (!(lo <= hi)) continue;
        const int64_t a = std::max<int64_t>(0, static_cast<int64_t>(std::ceil(lo - 1.5)));
        const int64_t b = std::min<int64_t>(scene.width - 1, static_cast<int64_t>(std::floor(hi + 0.5)));
        if (a <= b) tri.region.push_back({row, a, b});
      }
    }
    tri.cx = ((x_lo + x_hi) / 2) >> sub;
    tri.cy = ((y_lo + y_hi) / 2) >> sub;
    tri.extent = static_cast<long double>(std::max(x_hi - x_lo, y_hi - y_lo)) / static_cast<long double>(one);
    for (size_t i = 0; i < 3; ++i) {
      const ScreenVertex& s = screen.vertex[i];
      const double x = snapped_pixels(unit.vertex[i].x, sub);
      const double y = snapped_pixels(unit.vertex[i].y, sub);
      const double dx = x - static_cast<double>(tri.cx);
      // Window y grows with cdsim's y (rows read back top row first) unless --y-up.
      // glClipControl(GL_UPPER_LEFT) negates y between NDC and window.
      const bool negate_y = options.y_up != options.clip_upper_left;
      const double dy = negate_y ? static_cast<double>(tri.cy) - y : y - static_cast<double>(tri.cy);
      if (std::fabs(dx) >= half || std::fabs(dy) >= half) tri.gl_clipped = true;
      const float w = static_cast<float>(s.w);
      const float ndc_x = static_cast<float>(dx / half), ndc_y = static_cast<float>(dy / half);
      GlVertex& g = vertices[static_cast<size_t>(3 * t) + i];
      g.clip[0] = ndc_x * w;
      g.clip[1] = ndc_y * w;
      g.clip[2] = 0.0f;
      g.clip[3] = w;
      g.u = static_cast<float>(s.u);
      g.v = static_cast<float>(s.v);
      g.id = static_cast<float>(t);
      tri.max_u = std::max(tri.max_u, std::fabs(static_cast<long double>(s.u)));
      tri.max_v = std::max(tri.max_v, std::fabs(static_cast<long double>(s.v)));
      tri.q[i] = 1.0L / static_cast<long double>(s.w);
      tri.q_max = std::max(tri.q_max, tri.q[i]);
      tri.max_uq = std::max(tri.max_uq, std::fabs(static_cast<long double>(s.u)) * tri.q[i]);
      tri.max_vq = std::max(tri.max_vq, std::fabs(static_cast<long double>(s.v)) * tri.q[i]);
      // The window centre is an integer; its value only matters for float
      // rounding of the sum, so the largest a tile can give is used.
      for (double centre : {0.0, static_cast<double>(options.tile)}) {
        worst_position_error = std::max(worst_position_error, float_path_error(dx, w, half, centre));
        worst_position_error = std::max(worst_position_error, float_path_error(dy, w, half, centre));
      }
    }
    if (tri.gl_clipped) ++clipped;
    if (tri.edges.det != 0) {
      long double perimeter = 0;
      for (size_t i = 0; i < 3; ++i)
        perimeter += std::hypot(static_cast<long double>(tri.edges.a[i]),
                                static_cast<long double>(tri.edges.b[i])) / one;
      const long double twice_area =
          std::fabs(static_cast<long double>(tri.edges.det)) / (static_cast<long double>(one) * one);
      tri.shape = static_cast<long double>(tri.extent) * perimeter / twice_area;
    }
  }
  gl->upload(vertices);

  Stats stats;
  stats.du.reserve(static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height));
  stats.dv.reserve(stats.du.capacity());
  int64_t tiles = 0, batches = 0, draws = 0;
  std::vector<Texel> texels;
  for (int ty0 = 0; ty0 < scene.height; ty0 += tile_h) {
    for (int tx0 = 0; tx0 < scene.width; tx0 += tile_w) {
      ++tiles;
      const int64_t tx1 = std::min(scene.width, tx0 + tile_w) - 1;
      const int64_t ty1 = std::min(scene.height, ty0 + tile_h) - 1;
      // Greedy batching: a triangle joins the first batch none of whose
      // triangles' regions shares a pixel with its own region. One bit per
      // batch and pixel, 64 batches to a generation.
      std::vector<std::vector<int64_t>> batch_tris;
      std::vector<std::vector<uint64_t>> generations;
      const size_t tile_pixels = static_cast<size_t>(tile_w) * static_cast<size_t>(tile_h);
      for (int64_t t = 0; t < n; ++t) {
        const Tri& tri = tris[static_cast<size_t>(t)];
        const PixelBox& b = tri.box;
        if (tri.region.empty() || b.x_hi < tx0 || b.x_lo > tx1 || b.y_hi < ty0 || b.y_lo > ty1)
          continue;
        const auto for_each_pixel = [&](auto&& f) {
          for (const RowSpan& r : tri.region) {
            if (r.y < ty0 || r.y > ty1) continue;
            const int64_t lo = std::max<int64_t>(r.lo, tx0), hi = std::min(r.hi, tx1);
            for (int64_t x = lo; x <= hi; ++x)
              f(static_cast<size_t>((r.y - ty0) * tile_w + (x - tx0)));
          }
        };
        size_t chosen = SIZE_MAX;
        for (size_t g = 0; chosen == SIZE_MAX; ++g) {
          if (g == generations.size()) generations.emplace_back(tile_pixels, 0);
          uint64_t used = 0;
          for_each_pixel([&](size_t i) { used |= generations[g][i]; });
          if (~used == 0) continue;
          const int bit = __builtin_ctzll(~used);
          chosen = g * 64 + static_cast<size_t>(bit);
          for_each_pixel([&](size_t i) { generations[g][i] |= uint64_t{1} << bit; });
        }
        if (chosen >= batch_tris.size()) batch_tris.resize(chosen + 1);
        batch_tris[chosen].push_back(t);
      }

      for (const auto& batch : batch_tris) {
        ++batches;
        // The batch's rectangle: its regions' extent plus a margin, in which
        // every GL pixel must belong to a region.
        int64_t rx0 = tx1, rx1 = tx0, ry0 = ty1, ry1 = ty0;
        for (int64_t t : batch)
          for (const RowSpan& span : tris[static_cast<size_t>(t)].region) {
            if (span.y < ty0 || span.y > ty1) continue;
            rx0 = std::min(rx0, span.lo), rx1 = std::max(rx1, span.hi);
            ry0 = std::min(ry0, span.y), ry1 = std::max(ry1, span.y);
          }
        rx0 = std::max<int64_t>(tx0, rx0 - kMargin), rx1 = std::min(tx1, rx1 + kMargin);
        ry0 = std::max<int64_t>(ty0, ry0 - kMargin), ry1 = std::min(ty1, ry1 + kMargin);
        const int rect_w = static_cast<int>(rx1 - rx0 + 1), rect_h = static_cast<int>(ry1 - ry0 + 1);
        // Window rows of cdsim rows: row j of the tile is window row j (or, with
        // --y-up, tile_h - 1 - j).
        const auto window_row = [&](int64_t y) {
          return options.y_up ? tile_h - 1 - (y - ty0) : y - ty0;
        };
        const int64_t wy0 = std::min(window_row(ry0), window_row(ry1));
        const int wx0 = static_cast<int>(rx0 - tx0);
        gl->clear(wx0, static_cast<int>(wy0), rect_w, rect_h);
        stats.pixels_read += int64_t{rect_w} * rect_h;
        for (int64_t t : batch) {
          const Tri& tri = tris[static_cast<size_t>(t)];
          const int64_t vx = tri.cx - tx0 - half;
          const int64_t vy = options.y_up ? (ty0 + tile_h - tri.cy) - half : tri.cy - ty0 - half;
          if (vx < gl->limits().bounds_lo || vx > gl->limits().bounds_hi ||
              vy < gl->limits().bounds_lo || vy > gl->limits().bounds_hi) {
            std::cerr << fmt::format("gl_oracle: triangle {}: viewport origin ({}, {}) is outside "
                                     "GL's bounds [{}, {}]\n",
                                     t, vx, vy, gl->limits().bounds_lo, gl->limits().bounds_hi);
            return 1;
          }
          gl->draw(t, static_cast<int>(vx), static_cast<int>(vy), size);
          ++draws;
        }
        gl->read(wx0, static_cast<int>(wy0), rect_w, rect_h, texels);
        int64_t gl_total = 0, gl_in_regions = 0;
        for (const Texel& texel : texels) gl_total += texel.id >= 0;
        for (int64_t t : batch) {
          const Tri& tri = tris[static_cast<size_t>(t)];
          const ExactReference& ref = exact[static_cast<size_t>(t)];
          const float id = static_cast<float>(t);
          for (const RowSpan& span : tri.region) {
            const int64_t y = span.y;
            if (y < ty0 || y > ty1) continue;
            const int64_t row = window_row(y);
            const int64_t x0 = std::max<int64_t>(span.lo, tx0), x1 = std::min(span.hi, tx1);
            for (int64_t x = x0; x <= x1; ++x) {
              const Texel& texel =
                  texels[static_cast<size_t>((row - wy0) * rect_w + (x - tx0 - wx0))];
              if (tri.edges.det != 0)
                for (size_t i = 0; i < 3; ++i) stats.on_edge += edge_value(tri.edges, i, x, y) == 0;
              const bool by_gl = texel.id == id;
              const bool by_cdsim = covers(tri.edges, x, y);
              ++stats.region_pixels;
              gl_in_regions += by_gl;
              if (by_gl != by_cdsim) {
                (by_gl ? stats.gl_only : stats.cdsim_only) += 1;
                const Explanation why = explain(tri, x, y, options.y_up != options.clip_upper_left,
                                                worst_position_error < 0.5);
                stats.categories[std::string(by_gl ? "GL only: " : "cdsim only: ") + why.why] += 1;
                if (!why.expected) ++stats.unexpected;
                if (static_cast<int>(stats.shown.size()) < options.show)
                  stats.shown.push_back({t, x, y, by_gl, why.why});
                continue;
              }
              if (!by_gl) continue;
              ++stats.both;
              const ExactSample e = ref.at_pixel(x, y);
              const double du = static_cast<double>(std::fabs(texel.u - e.u));
              const double dv = static_cast<double>(std::fabs(texel.v - e.v));
              stats.du.push_back(static_cast<float>(du));
              stats.dv.push_back(static_cast<float>(dv));
              // The binary32 bound of docs/oracle.md, per pixel.
              long double q = 0, qx = 0, qy = 0;
              for (size_t i = 0; i < 3; ++i) {
                q += edge_value(tri.edges, i, x, y) * tri.q[i];
                qx += static_cast<long double>(tri.edges.a[i]) * tri.q[i];
                qy += static_cast<long double>(tri.edges.b[i]) * tri.q[i];
              }
              // q, qx, qy share the factor 1/det; the gradient is per subpixel.
              const long double g = std::hypot(qx, qy) * std::ldexp(1.0L, sub) / std::fabs(q);
              q = std::fabs(q / static_cast<long double>(tri.edges.det));
              const long double length = static_cast<long double>(x - tx0) + 0.5L +
                                         static_cast<long double>(row) + 0.5L + tri.extent;
              const long double rho = e.footprint;
              const auto bound = [&](long double value, long double max_abs, long double max_abs_q) {
                const long double terms[4] = {
                    max_abs + std::fabs(value),                          // inputs, final divide
                    (rho + std::fabs(value) * g) * length,               // plane evaluation
                    (max_abs_q + std::fabs(value) * tri.q_max) / q * tri.shape,  // plane setup
                    0};
                return static_cast<long double>(options.k) * kEps * (terms[0] + terms[1] + terms[2]);
              };
              const long double bu = bound(e.u, tri.max_u, tri.max_uq);
              const long double bv = bound(e.v, tri.max_v, tri.max_vq);
              const double ratio = static_cast<double>(std::max(du / bu, dv / bv));
              if (ratio > 1) ++stats.over_bound;
              const auto note = [&](Stats::Worst& w, double r) {
                w = {t, x, y, texel.u, texel.v, static_cast<double>(e.u), static_cast<double>(e.v),
                     static_cast<double>(bu), static_cast<double>(bv), r,
                     static_cast<double>(rho), static_cast<double>(g), static_cast<double>(length)};
              };
              if (ratio > stats.max_ratio) stats.max_ratio = ratio, note(stats.worst, ratio);
              if (std::max(du, dv) > std::max(stats.max_du, stats.max_dv)) note(stats.largest, ratio);
              stats.max_normalised = std::max(
                  stats.max_normalised,
                  std::max(du, dv) / std::max(1.0, static_cast<double>(rho)));
              stats.max_du = std::max(stats.max_du, du);
              stats.max_dv = std::max(stats.max_dv, dv);
            }
          }
        }
        const int64_t stray = gl_total - gl_in_regions;
        if (stray > 0) {
          stats.stray += stray;
          stats.gl_only += stray;
          stats.categories["GL only: outside the triangle's region (unexplained)"] += stray;
          stats.unexpected += stray;
        }
      }
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();

  const auto p99 = [](std::vector<float>& values) {
    if (values.empty()) return 0.0;
    const size_t k = static_cast<size_t>(0.99 * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
    return static_cast<double>(values[k]);
  };
  const double p99_du = p99(stats.du), p99_dv = p99(stats.dv);

  const bool coverage_ok = stats.unexpected == 0;
  const bool uv_ok = stats.over_bound == 0;
  std::cout << fmt::format("gl_oracle: scene {} ({}x{}, {} triangles)\n", scene.name, scene.width,
                           scene.height, n);
  std::cout << fmt::format("renderer: {} | {}\n", gl->renderer(), gl->version());
  std::cout << fmt::format("method: {} tile(s) of {}x{}, {} batches of disjoint regions, {} "
                           "draws, viewport {}x{} centred per triangle, rows {}\n",
                           tiles, tile_w, tile_h, batches, draws, size, size,
                           options.y_up ? "bottom-up (--y-up)" : "top-down (window y = cdsim y)");
  std::cout << fmt::format("positions: worst float-path error {:.4f} subpixel (llvmpipe rounds "
                           "exactly back to 16.8 while < 0.5); {} triangle(s) clipped by GL\n",
                           worst_position_error, clipped);
  std::cout << fmt::format("pixels compared: {} (triangle, pixel) pairs within 1 px of a "
                           "triangle; {} covered by both; {} centre-on-edge cases\n",
                           stats.region_pixels, stats.both, stats.on_edge);
  std::cout << fmt::format("coverage differences: {} (GL only {}, cdsim only {}), {} not expected\n",
                           stats.gl_only + stats.cdsim_only, stats.gl_only, stats.cdsim_only,
                           stats.unexpected);
  for (const auto& [what, count] : stats.categories)
    std::cout << fmt::format("  {:>9}  {}\n", count, what);
  for (const Difference& d : stats.shown)
    std::cout << fmt::format("  e.g. triangle {} pixel ({}, {}): {} ({})\n", d.triangle, d.x, d.y,
                             d.gl_covers ? "GL covers, cdsim does not" : "cdsim covers, GL does not",
                             d.why);
  std::cout << fmt::format("|du| texels: max {:.3e}  p99 {:.3e}\n", stats.max_du, p99_du);
  std::cout << fmt::format("|dv| texels: max {:.3e}  p99 {:.3e}\n", stats.max_dv, p99_dv);
  std::cout << fmt::format("footprint-normalised max(|du|,|dv|)/max(1,rho): max {:.3e}\n",
                           stats.max_normalised);
  std::cout << fmt::format("binary32 bound (K={}): worst |d|/bound {:.3f}, {} pixel(s) over\n",
                           options.k, stats.max_ratio, stats.over_bound);
  const auto show = [](const char* what, const Stats::Worst& w) {
    if (w.triangle < 0) return;
    std::cout << fmt::format("  {}: triangle {} pixel ({}, {}): GL ({:.9g}, {:.9g}) exact ({:.9g}, "
                             "{:.9g}), bound ({:.3g}, {:.3g}), rho {:.3g}, |grad q|/q {:.3g}, L {:.0f}\n",
                             what, w.triangle, w.x, w.y, w.gl_u, w.gl_v, w.exact_u, w.exact_v,
                             w.bound_u, w.bound_v, w.rho, w.g, w.length);
  };
  show("largest error", stats.largest);
  show("closest to bound", stats.worst);
  std::cout << fmt::format("time: {:.1f} s\n", seconds);
  const bool ok = coverage_ok && uv_ok;
  std::cout << "gl_oracle: " << (ok ? "PASS" : "FAIL") << '\n';
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"gl_oracle: compare cdsim's coverage and exact (u, v) with Mesa llvmpipe"};
  add_scene_options(&app, options.scene, options.scene_options);
  app.add_option("--tile", options.tile, "framebuffer tile size, pixels")
      ->check(CLI::Range(64, 8192))
      ->capture_default_str();
  app.add_option("--show", options.show, "coverage differences to list")->capture_default_str();
  app.add_option("--k", options.k, "constant K of the binary32 u, v bound")->capture_default_str();
  app.add_flag("--y-up", options.y_up,
               "experiment: map cdsim's top row to GL's top (window y up) instead of row 0");
  app.add_flag("--clip-upper-left", options.clip_upper_left,
               "experiment: glClipControl(GL_UPPER_LEFT)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "gl_oracle: " << e.what() << '\n';
    return 1;
  }
}
