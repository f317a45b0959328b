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
CorrectedValue correction_adder(const LineValue& own, const LineValue& neighbour, int64_t weight,
                                const Widths& widths);

}  // namespace cdsim
