#include "cost.hpp"

#include <algorithm>

#include "column_walker.hpp"

namespace cdsim {

int64_t register_bits(const Design& d, const Widths& w) {
  // Widths of the recurring registers.
  const int64_t q_plane = w.plane_bits + 2;                      // q values, sign and headroom
  const int64_t uv_plane = w.plane_bits + 2 + 16 + w.uv_in_frac;  // U = u q and V = v q values
  const int64_t coordinate = 14;                                 // pixel offsets and indices (8192)
  const int64_t output = 2 * (w.out_int + w.out_frac);
  const int64_t accumulator = std::max(w.t_int, w.s_int + 14) + accumulator_frac(w) + 1;
  const int64_t reciprocal_stage = w.recip_bits + 1 + 2 * uv_plane;  // q mantissa and U, V in flight
  const int64_t walker = 4 * coordinate;                         // offset, span low/high, pixel
  // q, U, V at the reference with steps along both axes.
  const int64_t full_planes = 3 * q_plane + 6 * uv_plane;
  switch (d.kind) {
    case Design::Kind::ConstantDepth: {
      const int64_t setup = 2 * q_plane + 4 * uv_plane + 2 * uv_plane + (w.g_frac + 2);
      const int64_t fill = w.recip_latency * reciprocal_stage;
      const int64_t column = coordinate /* r(o) */ + coordinate /* line index */ + w.d_frac + 1;
      const int64_t lines = (d.correction ? 2 : 1) * 2 * accumulator;
      return setup + fill + walker + column + lines + output;
    }
    case Design::Kind::Divide:
      return full_planes + walker + (q_plane + 2 * uv_plane) + w.recip_latency * reciprocal_stage +
             output;
    case Design::Kind::Kim: {
      const int64_t divisor = q_plane + w.uv_in_frac;
      // Per coordinate: N, S (numerator width), D, R (divisor width), I.
      const int64_t iteration = 2 * (2 * uv_plane + 2 * divisor + w.out_int);
      const int64_t fraction_stage = 2 * (2 * divisor + w.kim_frac);
      const int64_t fraction = (d.pipelined ? w.kim_frac : 1) * fraction_stage;
      return full_planes + walker + iteration + fraction + output;
    }
    case Design::Kind::Affine: {
      const int64_t value = w.t_int + w.s_frac;
      if (d.subdivision == 0)
        return 2 * (value + 2 * (w.s_int + w.s_frac)) + walker + 2 * accumulator + output;
      // End point, step and running value per coordinate, plus the divider.
      return full_planes + walker + 2 * 3 * value + w.recip_latency * reciprocal_stage + output;
    }
  }
  return 0;
}

}  // namespace cdsim
