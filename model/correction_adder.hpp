// Correction adder: the paper's linear correction between a pixel's line and
// its neighbour, u = u_line(k) + |t| (u_line(k') - u_line(k)), then rounding
// and saturation to the output format.
#pragma once

#include <cstdint>

#include "column_walker.hpp"

namespace cdsim {

struct CorrectedValue {
  int64_t u = 0, v = 0;  // output format
  bool saturated = false;
};

// Without a neighbour (no correction, or t = 0) pass the same value twice.
inline CorrectedValue correction_adder(const LineValue& own, const LineValue& neighbour,
                                       int64_t weight, const Widths& w) {
  const auto correct = [&](int64_t a, int64_t b) {
    if (a == b) return a;
    return a + static_cast<int64_t>(fx::shift_round(fx::Wide{weight} * (b - a), w.d_frac,
                                                    fx::Round::Nearest));
  };
  const int shift = accumulator_frac(w) - w.out_frac;
  const int64_t hi = (int64_t{1} << (w.out_int + w.out_frac - 1)) - 1;
  CorrectedValue out;
  out.u = fx::narrow_nearest_saturate(correct(own.u, neighbour.u), shift, -hi - 1, hi, &out.saturated);
  out.v = fx::narrow_nearest_saturate(correct(own.v, neighbour.v), shift, -hi - 1, hi, &out.saturated);
  return out;
}

}  // namespace cdsim
