// Shared helpers for the model tests: triangle builders, a brute-force
// coverage oracle, and an ideal long-double version of each design's
// algorithm (no fixed point), written independently of the model's datapath.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "pixel_coverage.hpp"
#include "exact.hpp"
#include "scan_unit.hpp"
#include "setup_engine.hpp"
#include "triangle.hpp"
#include "widths.hpp"

namespace cdsim::testing {

inline Widths wide_widths() {
  Widths w;
  w.uv_in_frac = 12;
  w.q_bits = 32;
  w.plane_bits = 48;
  w.g_frac = 30;
  w.recip_bits = 32;
  w.t_int = 20;
  w.t_frac = 24;
  w.s_int = 20;
  w.s_frac = 24;
  w.d_frac = 24;
  w.out_int = 20;
  w.out_frac = 16;
  w.table_depth = 8192;
  w.eps_frac = 30;
  w.persp_frac = 30;
  return w;
}

inline ScreenTriangle screen_triangle(std::array<std::array<double, 5>, 3> v) {
  ScreenTriangle t;
  for (size_t i = 0; i < 3; ++i) t.vertex[i] = {v[i][0], v[i][1], v[i][2], v[i][3], v[i][4]};
  return t;
}

// A random triangle in a viewport, with depth ratio up to `depth_ratio`.
inline ScreenTriangle random_triangle(std::mt19937_64& rng, double width, double height,
                                      double depth_ratio = 100.0, double texels = 2000.0) {
  std::uniform_real_distribution<double> x(-0.1 * width, 1.1 * width), y(-0.1 * height, 1.1 * height);
  std::uniform_real_distribution<double> log_w(0.0, std::log(depth_ratio));
  std::uniform_real_distribution<double> tex(-texels, texels);
  ScreenTriangle t;
  for (auto& v : t.vertex) v = {x(rng), y(rng), std::exp(log_w(rng)), tex(rng), tex(rng)};
  return t;
}

// All pixels of the viewport whose centres the triangle covers, by testing each one.
inline std::vector<std::pair<int64_t, int64_t>> brute_force_pixels(const UnitTriangle& t,
                                                                   const Widths& w, int width,
                                                                   int height) {
  const EdgeSet edges = make_edges(t, w.subpixel_bits);
  std::vector<std::pair<int64_t, int64_t>> out;
  for (int64_t y = 0; y < height; ++y)
    for (int64_t x = 0; x < width; ++x)
      if (covers(edges, x, y)) out.emplace_back(x, y);
  return out;
}

// cd-persp's 1 / (1 + x) as its table gives it, in long double: 1 + x doubled
// into m in [1, 2) when below 1, and the chord of 1/m between the points
// 1 / (1 + i / K), K = 2^table_log2, halved back.
inline long double chord_reciprocal(long double x, int table_log2) {
  const long double k = std::ldexp(1.0L, table_log2), y = 1 + x;
  const int shift = std::ilogb(y);  // 1 + x = m 2^shift, m in [1, 2)
  const long double m = std::ldexp(y, -shift);
  const long double i = std::floor((m - 1) * k), frac = (m - 1) * k - i;
  const long double lo = 1 / (1 + i / k), hi = 1 / (1 + (i + 1) / k);
  return std::ldexp(lo + (hi - lo) * frac, -shift);
}

// The ideal value of a constant-depth design at one pixel, in long double:
// the design's lines (slope g taken from the setup, as a parameter of the
// algorithm) evaluated exactly from the unit's own inputs, with no rounding.
struct IdealValue {
  long double u = 0, v = 0;
  // Largest |u_line(k') - u_line(k)| of the correction: the quantised weight
  // |t| (d_frac bits) is off by up to half an LSB of it.
  long double neighbour_gap = 0;
};

class IdealConstantDepth {
 public:
  IdealConstantDepth(const UnitTriangle& t, const Setup& setup, const Widths& w)
      : setup_(setup), w_(w) {
    const int sp = w.subpixel_bits;
    for (size_t i = 0; i < 3; ++i) {
      float qf;
      std::memcpy(&qf, &t.vertex[i].q_float, sizeof qf);
      q_[i] = qf;
      uq_[i] = q_[i] * std::ldexp(static_cast<long double>(t.vertex[i].u), -w.uv_in_frac);
      vq_[i] = q_[i] * std::ldexp(static_cast<long double>(t.vertex[i].v), -w.uv_in_frac);
      x_[i] = std::ldexp(static_cast<long double>(t.vertex[i].x), -sp);
      y_[i] = std::ldexp(static_cast<long double>(t.vertex[i].y), -sp);
    }
    det_ = (x_[1] - x_[0]) * (y_[2] - y_[0]) - (x_[2] - x_[0]) * (y_[1] - y_[0]);
  }

  // Barycentric interpolation of (q, U, V) at any point (x, y) in pixels.
  std::array<long double, 3> planes(long double x, long double y) const {
    std::array<long double, 3> out{0, 0, 0};
    for (size_t i = 0; i < 3; ++i) {
      const size_t a = (i + 1) % 3, b = (i + 2) % 3;
      const long double weight =
          ((x_[b] - x_[a]) * (y - y_[a]) - (y_[b] - y_[a]) * (x - x_[a])) / det_;
      out[0] += weight * q_[i];
      out[1] += weight * uq_[i];
      out[2] += weight * vq_[i];
    }
    return out;
  }

  // u, v on line `line` at column offset `offset`: U and V at the line's point
  // in that column, divided by q where the line crosses the reference column.
  IdealValue on_line(int64_t line, int64_t offset) const {
    const long double g = std::ldexp(static_cast<long double>(setup_.g), -w_.g_frac);
    const long double major0 = static_cast<long double>(setup_.major_lo) + 0.5L;
    const long double minor0 = static_cast<long double>(setup_.minor_lo) + 0.5L;
    const long double m = setup_.density;
    const long double minor_at_ref = minor0 + (static_cast<long double>(line) + phase()) / m;
    const long double minor_here = minor_at_ref + g * static_cast<long double>(offset);
    const long double major_here = major0 + static_cast<long double>(offset);
    const auto at = [&](long double major, long double minor) {
      return setup_.x_major ? planes(major, minor) : planes(minor, major);
    };
    const long double q_line = at(major0, minor_at_ref)[0];
    const auto p = at(major_here, minor_here);
    return {p[1] / q_line, p[2] / q_line};
  }

  long double q_on_line(int64_t line) const {
    const long double major0 = static_cast<long double>(setup_.major_lo) + 0.5L;
    const long double minor0 = static_cast<long double>(setup_.minor_lo) + 0.5L;
    const long double minor = minor0 + (static_cast<long double>(line) + phase()) / setup_.density;
    return (setup_.x_major ? planes(major0, minor) : planes(minor, major0))[0];
  }

  // The lines' phase in gaps: line k lies k + phi gaps from the reference
  // (the setup's phi, whose placement tests/line_phase_test.cpp checks).
  long double phase() const {
    return std::ldexp(static_cast<long double>(setup_.line_phase), -setup_.line_phase_bits);
  }

  // cd-persp: the exact 1 / (1 + x) instead of the table's.
  void set_persp_exact(bool exact) { exact_persp_ = exact; }

  IdealValue at_pixel(int64_t x, int64_t y) const {
    const int64_t major = setup_.x_major ? x : y, minor = setup_.x_major ? y : x;
    const int64_t offset = major - setup_.major_lo;
    const long double g = std::ldexp(static_cast<long double>(setup_.g), -w_.g_frac);
    const long double shift = setup_.density * g * static_cast<long double>(offset) + phase();
    const long double rounded = std::floor(shift + 0.5L);
    const long double t = rounded - shift;  // line spacings from the pixel's line
    const int64_t line =
        setup_.density * (minor - setup_.minor_lo) - static_cast<int64_t>(rounded);
    const IdealValue own = on_line(line, offset);
    if (!setup_.correction || t == 0) return own;
    const IdealValue other = on_line(line + (t > 0 ? 1 : -1), offset);
    long double a = std::fabs(t);
    if (setup_.persp) {
      // cd-persp's weight |t| + |t|(1 - |t|) e r, e = q_k' / q_k - 1, with r
      // the table's chord interpolation of 1 / (1 + |t| e), or (exact_persp_)
      // 1 / (1 + |t| e) itself, which makes the weight the projective one.
      const long double e = q_on_line(line + (t > 0 ? 1 : -1)) / q_on_line(line) - 1;
      const long double r = exact_persp_ ? 1 / (1 + a * e) : chord_reciprocal(a * e, w_.persp_table_log2);
      a = a + a * (1 - a) * e * r;
    }
    return {own.u + a * (other.u - own.u), own.v + a * (other.v - own.v),
            std::max(std::fabs(other.u - own.u), std::fabs(other.v - own.v))};
  }

 private:
  Setup setup_;
  Widths w_;
  bool exact_persp_ = false;
  std::array<long double, 3> q_{}, uq_{}, vq_{}, x_{}, y_{};
  long double det_ = 0;
};

inline std::vector<Fragment> run_unit(const Design& design, const Widths& w, int width, int height,
                                      const UnitTriangle& t, TriangleRecord* record = nullptr) {
  ScanUnit unit(design, w, width, height);
  std::vector<Fragment> fragments;
  const TriangleRecord r = unit.run(t, &fragments);
  if (record) *record = r;
  return fragments;
}

}  // namespace cdsim::testing
