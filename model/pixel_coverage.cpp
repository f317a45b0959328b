#include "pixel_coverage.hpp"

#include <algorithm>
#include <limits>

#include "fixed.hpp"

namespace cdsim {

EdgeSet make_edges(const UnitTriangle& t, int subpixel_bits) {
  EdgeSet e;
  e.subpixel_bits = subpixel_bits;
  const auto& v = t.vertex;
  e.det = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[2].x - v[0].x) * (v[1].y - v[0].y);
  const int64_t orientation = e.det < 0 ? -1 : 1;
  for (size_t i = 0; i < 3; ++i) {
    // Edge i runs from vertex i+1 to vertex i+2, opposite vertex i, so that
    // E_i is vertex i's barycentric weight times det.
    const UnitVertex& from = v[(i + 1) % 3];
    const UnitVertex& to = v[(i + 2) % 3];
    const int64_t dx = to.x - from.x;
    const int64_t dy = to.y - from.y;
    e.a[i] = -dy * orientation;
    e.b[i] = dx * orientation;
    e.c[i] = (dy * from.x - dx * from.y) * orientation;
    // The inside lies along the normal (a, b). A top edge is horizontal with the
    // inside below it (+y, screen y points down); a left edge has the inside to
    // its right (+x).
    const bool top = e.a[i] == 0 && e.b[i] > 0;
    const bool left = e.a[i] > 0;
    e.threshold[i] = (top || left) ? 0 : 1;
  }
  return e;
}

PixelBox bounding_box(const UnitTriangle& t, int subpixel_bits, int viewport_width,
                      int viewport_height) {
  int64_t min_x = std::numeric_limits<int64_t>::max(), max_x = std::numeric_limits<int64_t>::min();
  int64_t min_y = min_x, max_y = max_x;
  for (const auto& v : t.vertex) {
    min_x = std::min(min_x, v.x), max_x = std::max(max_x, v.x);
    min_y = std::min(min_y, v.y), max_y = std::max(max_y, v.y);
  }
  const int64_t one = int64_t{1} << subpixel_bits;
  const int64_t half = one >> 1;
  PixelBox box;
  // Pixel i has its centre at i*one + half: the first centre at or after min.
  box.x_lo = std::max<int64_t>(0, static_cast<int64_t>(fx::ceil_div(min_x - half, one)));
  box.x_hi = std::min<int64_t>(viewport_width - 1, static_cast<int64_t>(fx::floor_div(max_x - half, one)));
  box.y_lo = std::max<int64_t>(0, static_cast<int64_t>(fx::ceil_div(min_y - half, one)));
  box.y_hi = std::min<int64_t>(viewport_height - 1, static_cast<int64_t>(fx::floor_div(max_y - half, one)));
  return box;
}

bool covers(const EdgeSet& e, int64_t pixel_x, int64_t pixel_y) {
  if (e.det == 0) return false;
  const int64_t px = pixel_centre(pixel_x, e.subpixel_bits);
  const int64_t py = pixel_centre(pixel_y, e.subpixel_bits);
  for (size_t i = 0; i < 3; ++i)
    if (e.a[i] * px + e.b[i] * py + e.c[i] < e.threshold[i]) return false;
  return true;
}

Span covered_span(const EdgeSet& e, bool x_major, int64_t fixed_pixel) {
  Span span{std::numeric_limits<int64_t>::min() / 4, std::numeric_limits<int64_t>::max() / 4};
  if (e.det == 0) return Span{};
  const int64_t fixed = pixel_centre(fixed_pixel, e.subpixel_bits);
  const int64_t half = int64_t{1} << (e.subpixel_bits - 1);
  for (size_t i = 0; i < 3; ++i) {
    const int64_t fixed_coef = x_major ? e.a[i] : e.b[i];
    const int64_t free_coef = x_major ? e.b[i] : e.a[i];
    // E(j) = base + step*j for the free pixel index j.
    const int64_t base = fixed_coef * fixed + free_coef * half + e.c[i];
    const int64_t step = free_coef * (int64_t{1} << e.subpixel_bits);
    const int64_t need = e.threshold[i] - base;  // step*j >= need
    if (step > 0) {
      span.lo = std::max(span.lo, static_cast<int64_t>(fx::ceil_div(need, step)));
    } else if (step < 0) {
      span.hi = std::min(span.hi, static_cast<int64_t>(fx::floor_div(-need, -step)));
    } else if (need > 0) {
      return Span{};
    }
  }
  return span;
}

}  // namespace cdsim
