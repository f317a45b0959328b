// The exact per-pixel-divide baseline (SPEC §7): q, U and V from the
// normalised planes at every pixel, one pipelined reciprocal, two multiplies.
#pragma once

#include "correction_adder.hpp"
#include "setup_engine.hpp"

namespace cdsim {

CorrectedValue divide_pixel(const Setup& setup, int64_t major_offset, int64_t minor_offset,
                            const Widths& widths, uint32_t* flags);

}  // namespace cdsim
