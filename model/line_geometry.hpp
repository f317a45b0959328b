// The geometry behind a constant-depth triangle's flags (issue 41,
// docs/robustness.md "Flagged triangles"): how far its farthest point lies
// from the horizon of its plane, how deep it reaches, and the T and S ranges
// its table lines need. Measured in long double from the exact planes (SPEC
// §2) and the lines the setup engine fills, not from the datapath's values,
// so that it says what a format must hold rather than what it held.
#pragma once

#include <cstdint>

#include "setup_engine.hpp"
#include "triangle.hpp"
#include "widths.hpp"

namespace cdsim {

struct LineGeometry {
  bool x_major = true;
  // far w / near w over the three vertices.
  double depth_ratio = 1;
  // The far vertex's distance to the horizon (q = 0) of its plane, in line
  // gaps (1 / density pixels along the minor axis). A covered pixel and its
  // line lie no farther than the far vertex, but its correction neighbour
  // may lie one line beyond it. Infinite for a plane parallel to the screen.
  double horizon_gaps = 0;
  int64_t lines = 0;         // lines the table holds (covered pixels and their neighbours)
  int64_t past_horizon = 0;  // of those, lines with q <= 0: their entries cannot exist
  // The largest |T| and |S| (texels, the larger of u and v) over the held
  // lines with q > 0, and the signed integer bits that holds them (the
  // t_int and s_int they need).
  double t_max = 0, s_max = 0;
  int t_int_needed = 1, s_int_needed = 1;
};

// `setup` is setup_engine()'s for `unit` under a constant-depth design.
LineGeometry line_geometry(const ScreenTriangle& screen, const UnitTriangle& unit, const Setup& setup,
                           const Widths& widths);

// The signed integer bits that hold every value of magnitude `largest`
// (round to nearest: 1 for |x| < 1/2 and so on), as t_int and s_int count them.
int signed_int_bits_for(double largest);

}  // namespace cdsim
