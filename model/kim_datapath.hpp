// The Kim-style datapath (SPEC §6), a reconstruction from the public abstract
// of Kim & Kim 2008: along a span, u = N / D with N = U and D = q (times
// 2^uv_in_frac) stepping by constants; the integer part I is kept by a
// midpoint (Pitteway-style) iteration with remainder R = N - I D, 0 <= R < D,
// one unit step of I per cycle; the fraction is kim_frac bits of R / D by
// restoring division. See docs/designs.md; the RTL is rtl/kim_datapath.sv.
#pragma once

#include "correction_adder.hpp"
#include "setup_engine.hpp"

namespace cdsim {

struct KimPixel {
  CorrectedValue value;     // output format
  int64_t integer_u = 0;    // I for u and v: the iteration's state after this pixel
  int64_t integer_v = 0;
  bool depth_out = false;   // D <= 0: no steps, I held, output 0
};

// The pixel's I and fraction. The iteration's result is defined by its
// invariant 0 <= R < D, so I = floor(N / D) exactly, clamped to the out_int
// register; the number of unit steps it took from the previous pixel is
// |I - I_previous|, which the timing layer charges. R / D is then divided to
// kim_frac bits (truncating, as restoring division does) and rounded to the
// output format. A pixel with D <= 0 raises depth_range, outputs 0 and takes
// no steps: I is the previous pixel's (`previous`), or 0 at a span's first
// pixel (previous = nullptr), where the span division does not run.
KimPixel kim_pixel(const Setup& setup, int64_t major_offset, int64_t minor_offset,
                   const Widths& widths, const KimPixel* previous, uint32_t* flags);

}  // namespace cdsim
