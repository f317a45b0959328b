// The affine baselines (SPEC §7): plain affine interpolation of u and v in
// screen space, and Quake-style subdivided affine, which divides exactly at
// every N-th pixel of a span and interpolates linearly in between.
#pragma once

#include "correction_adder.hpp"
#include "divide_datapath.hpp"
#include "setup_engine.hpp"
#include "triangle.hpp"

namespace cdsim {

// Affine planes of u and v (not u/w), in (t_int, s_frac) at the reference
// pixel and S format per pixel along each axis.
struct AffinePlanes {
  int64_t u_ref = 0, v_ref = 0;
  int64_t u_major = 0, u_minor = 0, v_major = 0, v_minor = 0;
  bool saturated = false;
};
AffinePlanes affine_setup(const UnitTriangle& triangle, const Setup& setup, const Widths& widths);

CorrectedValue affine_pixel(const AffinePlanes& planes, int64_t major_offset, int64_t minor_offset,
                            const Widths& widths);

// The accumulator format of the affine designs: t_int integer bits, s_frac fraction bits.
inline fx::Format affine_format(const Widths& w) { return {w.t_int, w.s_frac, true}; }

// u, v between two exact end points a (position 0) and b (position length),
// at `position`: a + position * round((b - a) / length), in affine_format,
// then rounded to the output format.
CorrectedValue interpolate_segment(const CorrectedValue& a, const CorrectedValue& b, int64_t length,
                                   int64_t position, const Widths& widths);

// quad-subN (docs/designs.md): a span's segments. From `first` with `remaining`
// pixels left to the span's last, the next segment is N pixels long while at
// least N remain, else the largest power of two <= remaining (an 11-pixel
// remainder of quad-sub16 is 8 + 2 + 1).
int64_t quadratic_segment_length(int64_t remaining, int64_t segment);

// u, v on the quadratic through the exact points a (position 0), m (length / 2)
// and b (length) of a segment whose length is a power of two, at `position`
// (0 .. length), evaluated exactly (the forward differences of
// rtl/quad_sub_datapath.sv are exact) and rounded once to the output format.
// A 1-pixel segment has no middle point: a at 0, b at 1.
CorrectedValue quadratic_segment(const CorrectedValue& a, const CorrectedValue& m, const CorrectedValue& b,
                                 int64_t length, int64_t position, const Widths& widths);

}  // namespace cdsim
