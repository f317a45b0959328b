// Triangles at the two boundaries of the unit: the screen-space triangle the
// front end produces (floating point), and the snapped, quantised triangle that
// reaches the unit's input port.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "widths.hpp"

namespace cdsim {

// One vertex after transform, clipping, perspective divide and viewport.
struct ScreenVertex {
  double x = 0, y = 0;  // pixels, y down, not yet snapped
  double w = 1;         // clip-space w (> 0 after clipping)
  double u = 0, v = 0;  // texels
};

struct ScreenTriangle {
  std::array<ScreenVertex, 3> vertex;
  std::string origin;  // where it came from, for messages ("mesh triangle 12")
};

// One vertex at the unit's input port.
struct UnitVertex {
  int64_t x = 0, y = 0;    // snapped, subpixel_bits fraction bits
  uint32_t q_float = 0;    // 1/w as IEEE-754 binary32 bits
  int64_t u = 0, v = 0;    // texels, uv_in_frac fraction bits
};

struct UnitTriangle {
  std::array<UnitVertex, 3> vertex;
};

// Refused input: the message names the triangle and what is wrong with it.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Screen coordinates and texture coordinates must stay below this many
// pixels / texels in magnitude (s16 integer part, SPEC §1 and §4).
inline constexpr double kCoordinateLimit = 32768.0;

// Snaps and quantises a screen triangle for the unit. Throws InputError for
// NaN, infinity, w <= 0 or coordinates out of range; `index` names it.
UnitTriangle to_unit(const ScreenTriangle& triangle, const Widths& widths, size_t index);

// The snapped position of a vertex in pixels, exactly as the unit sees it.
inline double snapped_pixels(int64_t raw, int subpixel_bits) {
  return static_cast<double>(raw) / static_cast<double>(int64_t{1} << subpixel_bits);
}

}  // namespace cdsim
