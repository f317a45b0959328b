// Coverage by three integer edge functions with the top-left rule (SPEC §1).
// Shared by the column walker and the exact reference, and checked in tests
// against a brute-force per-pixel test.
#pragma once

#include <array>
#include <cstdint>

#include "triangle.hpp"

namespace cdsim {

struct PixelBox {
  int64_t x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;  // inclusive pixel indices
  bool empty() const { return x_lo > x_hi || y_lo > y_hi; }
  int64_t width() const { return x_hi - x_lo + 1; }
  int64_t height() const { return y_hi - y_lo + 1; }
};

struct Span {
  int64_t lo = 0, hi = -1;  // inclusive
  bool empty() const { return lo > hi; }
};

// E_i(px, py) = a*px + b*py + c in subpixel units, oriented so that the
// inside is E_i >= threshold_i, with threshold 0 on top and left edges and 1
// elsewhere (E is an integer, so E >= 1 means strictly inside).
struct EdgeSet {
  std::array<int64_t, 3> a{}, b{}, c{}, threshold{};
  int64_t det = 0;  // twice the signed area in subpixel units; 0 covers nothing
  int subpixel_bits = 8;
};

EdgeSet make_edges(const UnitTriangle& triangle, int subpixel_bits);

// Pixels whose centres the snapped triangle's extent reaches, clipped to the viewport.
PixelBox bounding_box(const UnitTriangle& triangle, int subpixel_bits, int viewport_width,
                      int viewport_height);

// Pixel-centre coordinate of pixel index i, in subpixel units.
inline int64_t pixel_centre(int64_t i, int subpixel_bits) {
  return i * (int64_t{1} << subpixel_bits) + (int64_t{1} << (subpixel_bits - 1));
}

bool covers(const EdgeSet& edges, int64_t pixel_x, int64_t pixel_y);

// The covered pixels along one column (x_major: fixed x, span of y) or one row
// (fixed y, span of x), not yet clipped to any box.
Span covered_span(const EdgeSet& edges, bool x_major, int64_t fixed_pixel);

}  // namespace cdsim
