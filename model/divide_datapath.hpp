// The exact per-pixel-divide baseline (SPEC §7): q, U and V from the
// normalised planes at a pixel, one pipelined reciprocal, two multiplies.
// affine-subN uses the same datapath for its segment end points.
#pragma once

#include "correction_adder.hpp"
#include "setup_engine.hpp"

namespace cdsim {

// u, v at the pixel (major_offset, minor_offset from the reference), narrowed
// to `format` (round to nearest, saturate).
CorrectedValue divide_uv(const Setup& setup, int64_t major_offset, int64_t minor_offset,
                         const Widths& widths, const fx::Format& format, uint32_t* flags);

inline CorrectedValue divide_pixel(const Setup& setup, int64_t major_offset, int64_t minor_offset,
                                   const Widths& widths, uint32_t* flags) {
  return divide_uv(setup, major_offset, minor_offset, widths, widths.out_format(), flags);
}

}  // namespace cdsim
