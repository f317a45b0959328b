// Correction adder: u_line = T_k + o S_k for the pixel's line and its
// neighbour, the paper's linear correction u = u_line(k) + |t| (u_line(k') -
// u_line(k)), then rounding and saturation to the output format, and the
// fragment's flags. A flagged neighbour entry is never used (it would spread a
// bad value): the pixel keeps its own line's value and says so. Twin of
// rtl/correction_adder.sv.
#pragma once

#include <cstdint>

#include "column_walker.hpp"
#include "design.hpp"

namespace cdsim {

struct CorrectedValue {
  int64_t u = 0, v = 0;  // output format
  bool saturated = false;
};

// own + round(weight (other - own) 2^-d_frac), narrowed to the output format.
// Without a neighbour pass the same value twice.
inline CorrectedValue linear_correction(const LineValue& own, const LineValue& neighbour,
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

struct CorrectedFragment {
  CorrectedValue value;
  uint32_t flags = 0;  // the own entry's flags, neighbour_dropped, output_saturated
};

// One pixel: its own entry and, when correct (a design with correction and a
// pixel off its line), the neighbour entry.
inline CorrectedFragment correction_adder(const TableEntry& own_entry,
                                          const TableEntry* neighbour_entry, int64_t offset,
                                          int64_t weight, const Widths& w) {
  CorrectedFragment out;
  out.flags = own_entry.flags;
  const LineValue own = line_value(own_entry, offset, w);
  LineValue other = own;
  if (neighbour_entry) {
    if (neighbour_entry->flags == 0)
      other = line_value(*neighbour_entry, offset, w);
    else
      out.flags |= flag::kNeighbourDropped;
  }
  out.value = linear_correction(own, other, weight, w);
  if (out.value.saturated) out.flags |= flag::kOutputSaturated;
  return out;
}

}  // namespace cdsim
