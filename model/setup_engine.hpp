// Setup engine: plane equations, orientation, slope g, per-triangle
// normalisation, line range, and the per-line table fill (one reciprocal and
// four multiplies per line). Plain functions of values; cycles are counted by
// the caller (scan_unit).
#pragma once

#include <array>
#include <cstdint>

#include "pixel_coverage.hpp"
#include "derived_widths.hpp"
#include "design.hpp"
#include "fixed.hpp"
#include "widths.hpp"

namespace cdsim {

// Planes of q, U = u q and V = v q, normalised by the triangle's shared shift,
// at the reference pixel centre and per pixel along the major and minor axis.
struct Plane {
  fx::Wide at_ref = 0, per_major = 0, per_minor = 0;
  fx::Wide per_line = 0;  // per_minor / density

  // The value at a pixel, offsets from the reference pixel along each axis (exact).
  fx::Wide at(int64_t major_offset, int64_t minor_offset) const {
    return at_ref + fx::Wide{major_offset} * per_major + fx::Wide{minor_offset} * per_minor;
  }
};

// One edge's span end, tracked from column to column without division (the
// RTL's column walker): floor(N / step) and its remainder at the first column,
// and the per-column step of floor(.) with its remainder (docs/rtl.md).
struct EdgeTracker {
  int kind = 0;            // 0: free coefficient 0; 1: bounds the span below; 2: above
  int64_t bound = 0;       // floor(N / step), N = E - threshold at the column's pixel 0
  int64_t remainder = 0;   // N - bound step, in [0, step)
  int64_t step = 1;        // |free coefficient| 2^subpixel_bits (2^subpixel_bits for kind 0)
  int64_t slope = 0;       // floor(fixed 2^subpixel_bits / step)
  int64_t slope_remainder = 0;
};

struct Setup {
  bool empty = true;          // zero area or no pixel centre in the box: nothing to walk
  bool x_major = true;        // lines are x-major: the walker visits columns
  int64_t g = 0;              // slope, s2.g_frac
  int density = 1;            // lines per pixel
  bool correction = false;
  bool persp = false;         // cd-persp: the fill also computes eps per line
  PixelBox box;               // pixels to walk, clipped to the viewport
  int64_t major_lo = 0, major_count = 0;  // walked columns (x-major) or rows
  int64_t minor_lo = 0, minor_hi = -1;    // the other axis of the box
  int shift = 0;              // per-triangle normalisation: planes were scaled by 2^-shift
  Plane q, u, v;
  fx::Wide step_u = 0, step_v = 0;  // numerators of S: U_major + g U_minor, normalised
  int64_t pixel_line_lo = 0, pixel_line_hi = -1;  // lines covered pixels can use
  // The lines' phase phi in line_phase_bits fraction bits of a line gap, in
  // [0, 1): line k lies at k + phi line gaps from the reference centre along
  // the minor axis (docs/robustness.md, "The line phase"). 0 but for a
  // constant-depth triangle whose farthest line would otherwise lie within
  // half a gap of its horizon, or past it.
  int64_t line_phase = 0;
  int line_phase_bits = 0;
  // A design with a divide fallback: this triangle lies within
  // 2^fallback_gaps_log2 line gaps of its horizon and is walked per pixel by
  // divide's datapath, not through the table.
  bool fallback = false;
  EdgeSet edges;
  std::array<EdgeTracker, 3> edge_trackers{};  // per edge, at the first column (major_lo)
  uint32_t flags = 0;
  int fill_q_bits = 127, fill_uv_bits = 127;  // the fill accumulators' widths (derived_widths)
  int pixel_q_bits = 127, pixel_uv_bits = 127;  // the per-pixel plane accumulators' widths
};

// The setup engine's stages, as rtl/setup_stage_a.sv .. setup_stage_d.sv and
// rtl/setup_dividers.sv split it (docs/rtl.md, "Setup engine"). Each takes
// what the stages before it registered; setup_engine() runs them in order.
struct SetupStageA {
  bool empty = true;  // zero area or no pixel centre in the box: the later stages do not run
  EdgeSet edges;
  PixelBox box;
  std::array<fx::Wide, 3> q{}, uq{}, vq{};  // normalised 1/w, U = u q, V = v q at the vertices
  fx::Wide ref_x = 0, ref_y = 0;             // the reference pixel centre relative to vertex 0
  uint32_t flags = 0;                        // kDepthRange when a 1/w underflows
};
// A plane's coefficients per subpixel, scaled by det and signed so that q |det| > 0.
struct PlaneCoefficients {
  fx::Wide x = 0, y = 0;
};
struct SetupStageB {
  PlaneCoefficients q, u, v;
  fx::Wide q_peak = 0;   // the largest q |det|
  fx::Wide q_floor = 0;  // the smallest: the far vertex's plane value (the line phase's test)
};
struct SetupStageC {
  fx::Wide q_at_ref = 0, u_at_ref = 0, v_at_ref = 0;  // exact, before the shift
  bool x_major = true;
  int shift = 0;
};
struct SetupDividers {
  int64_t g = 0;
  std::array<EdgeTracker, 3> edge_trackers{};
};
SetupStageA setup_stage_a(const UnitTriangle& triangle, const Widths& widths, const DerivedWidths& derived,
                          int viewport_width, int viewport_height);
SetupStageB setup_stage_b(const UnitTriangle& triangle, const SetupStageA& a, const DerivedWidths& derived);
SetupStageC setup_stage_c(const SetupStageA& a, const SetupStageB& b, const Widths& widths,
                          const DerivedWidths& derived);
SetupDividers setup_dividers(const SetupStageA& a, const SetupStageB& b, const SetupStageC& c,
                             const Widths& widths, const DerivedWidths& derived);
Setup setup_stage_d(const UnitTriangle& triangle, const SetupStageA& a, const SetupStageB& b,
                    const SetupStageC& c, const SetupDividers& dividers, const Design& design,
                    const Widths& widths, const DerivedWidths& derived);

// The per-triangle normalisation of the vertices' 1/w: the three binary32
// mantissas aligned to the largest exponent, rounded to q_bits (the shared
// exponent cancels in u = U/q and is dropped). 0 when a 1/w underflows.
std::array<fx::Wide, 3> normalised_q(const UnitTriangle& triangle, const Widths& widths);

// `derived` is derive(widths): a unit derives it once, not per triangle (it
// includes the setup schedule).
Setup setup_engine(const UnitTriangle& triangle, const Design& design, const Widths& widths,
                   const DerivedWidths& derived, int viewport_width, int viewport_height);
Setup setup_engine(const UnitTriangle& triangle, const Design& design, const Widths& widths,
                   int viewport_width, int viewport_height);

// 1/q as mantissa * 2^-(recip_bits + exponent), mantissa in (2^(recip_bits-1), 2^recip_bits].
struct Reciprocal {
  int64_t mantissa = 0;
  int exponent = 0;
  bool out_of_range = false;  // q <= 0: replaced by the smallest positive q
};
Reciprocal reciprocal(fx::Wide q, int recip_bits);

// numerator 2^-numerator_frac / q, by the reciprocal r of q, to `format`
// (round to nearest, saturate; *saturated is sticky). The numerator is first
// narrowed to the format's fraction bits plus guard_bits and one integer bit
// more than the format (its value is 1 to 2 times the quotient's, since
// q lies in [2^e, 2^(e+1))): round to nearest, saturate, which only happens
// where the quotient saturates too. Its product with the mantissa is then
// rounded once more, by a constant shift. The first rounding adds at most
// 2^-guard_bits of an ulp, and the product is (format bits + 1 + guard_bits)
// x (recip_bits + 1) bits whatever the numerator's width (rtl/
// reciprocal_product.sv; docs/choices.md).
fx::Wide quotient(fx::Wide numerator, int numerator_frac, const Reciprocal& r, int recip_bits,
                  const fx::Format& format, int guard_bits, bool* saturated);

struct TableEntry {
  int64_t t_u = 0, t_v = 0;  // (u, v) where line k crosses the reference column, T format
  int64_t s_u = 0, s_v = 0;  // (u, v) step per column along the line, S format
  // kTableSaturated and/or kDepthRange when this entry left its formats. A
  // flagged entry raises its flags on every fragment that uses it, and is never
  // used as a correction neighbour.
  uint32_t flags = 0;
  // cd-persp: eps = q_line w_k, the relative step of q from line k to k + 1
  // (s<eps_int>.eps_frac, symmetric: -eps is representable). Its saturation is kept
  // apart from flags, since only a pixel on this line uses it, never its
  // neighbours; such a pixel raises kTableSaturated.
  int64_t eps = 0;
  bool eps_saturated = false;
};

// Computes table entry k (line k relative to the reference pixel).
TableEntry fill_line(const Setup& setup, int64_t line, const Widths& widths);

// A plane's value on line k, k + phi gaps from the reference: at_ref plus
// (k + phi) per_line, the product rounded to nearest once (rtl/setup_fill.sv:
// stage E's product with the first line; later lines add per_line exactly).
fx::Wide plane_on_line(const Setup& setup, const Plane& plane, int64_t line);

}  // namespace cdsim
