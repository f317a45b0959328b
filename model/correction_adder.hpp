// Correction adder: u_line = T_k + o S_k for the pixel's line and its
// neighbour, the paper's linear correction u = u_line(k) + |t| (u_line(k') -
// u_line(k)), then rounding and saturation to the output format, and the
// fragment's flags. A flagged neighbour entry is never used (it would spread a
// bad value): the pixel keeps its own line's value and says so. Twin of
// rtl/correction_adder.sv.
#pragma once

#include <algorithm>
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
template <class Int>
inline CorrectedValue linear_correction(const LineValueOf<Int>& own, const LineValueOf<Int>& neighbour,
                                        int64_t weight, const Widths& w) {
  const auto correct = [&](Int a, Int b) {
    if (a == b) return a;
    return a + static_cast<Int>(fx::shift_round(fx::Wide{weight} * (b - a), w.d_frac,
                                                fx::Round::Nearest));
  };
  const int shift = accumulator_frac(w) - w.out_frac;
  const int64_t hi = (int64_t{1} << (w.out_int + w.out_frac - 1)) - 1;
  CorrectedValue out;
  out.u = fx::narrow_nearest_saturate(correct(own.u, neighbour.u), shift, -hi - 1, hi, &out.saturated);
  out.v = fx::narrow_nearest_saturate(correct(own.v, neighbour.v), shift, -hi - 1, hi, &out.saturated);
  return out;
}

// cd-persp: the perspective-correct weight t' = |d| (1 + e) / (1 + |d| e)
// toward the neighbour k' = k + direction, where e = q_k' / q_k - 1 =
// direction eps_k (the own line's table entry). Without a division:
//   t' = |d| + c e r,  c = |d| (1 - |d|) (per column),  r ~ 1 / (1 + x),  x = |d| e,
// r = 2^-s / m from a table of 1/m, m = (1 + x) 2^-s in [1, 2),
// K = 2^persp_table_log2 segments, linear between entries (persp_reciprocal).
// x, 1/m and c e carry persp_frac fraction bits, each rounded to nearest
// (m truncated); the 2^-s joins the last rounding, so t' is rounded once to
// d_frac bits and clamped to [0, 1], where the true t' lies. docs/designs.md
// gives the bounds. Twin of rtl/correction_adder.sv.

// Entry i of the table: 1 / (1 + i / K) at persp_frac bits, i = 0 .. K.
inline int64_t persp_table_entry(int64_t i, const Widths& w) {
  const int64_t k = int64_t{1} << w.persp_table_log2;
  // round(2^pf K / (K + i)), ties up.
  return static_cast<int64_t>(((fx::Wide{k} << (w.persp_frac + 1)) / (k + i) + 1) / 2);
}

// 1 / (1 + x) = reciprocal 2^-shift for x in [-1/2, 2^(eps_int - 2)), both
// at persp_frac bits: 1 + x = m 2^shift with m in [1, 2) (shift = -1 doubles
// it exactly; a positive shift truncates m to persp_frac fraction bits), 1/m
// taken between two table entries.
struct PerspReciprocal {
  int64_t reciprocal = 0;  // 1/m in (1/2, 1], persp_frac bits
  int shift = 0;           // -1 .. eps_int - 2
};
inline PerspReciprocal persp_reciprocal(int64_t x, const Widths& w) {
  const int pf = w.persp_frac, lg = w.persp_table_log2;
  const int64_t y = (int64_t{1} << pf) + x;  // > 0
  PerspReciprocal out;
  out.shift = fx::bit_length(y) - 1 - pf;
  const int64_t m = out.shift < 0 ? 2 * y : y >> out.shift;
  const int64_t f = m - (int64_t{1} << pf);  // m - 1, in [0, 2^pf)
  const int fine = pf - lg;                  // bits between entries
  const int64_t i = f >> fine, frac = f & ((int64_t{1} << fine) - 1);
  const int64_t lo = persp_table_entry(i, w), hi = persp_table_entry(i + 1, w);
  out.reciprocal = lo + static_cast<int64_t>(fx::shift_round(fx::Wide{hi - lo} * frac, fine, fx::Round::Nearest));
  return out;
}

inline int64_t persp_weight(int64_t weight, int direction, int64_t eps, const Widths& w) {
  using fx::Round;
  using fx::Wide;
  const int pf = w.persp_frac, df = w.d_frac;
  const Wide e = direction > 0 ? eps : -eps;                // s<eps_int>.eps_frac
  const Wide c = Wide{weight} * ((Wide{1} << df) - weight);  // 2 d_frac bits
  // |d| <= 1/2 and |e| < 2^(eps_int - 1), so x < 2^(eps_int - 2); x < -1/2
  // only by rounding (e = -1 is a neighbour at q = 0, which is never used).
  const Wide x = std::clamp<Wide>(fx::shift_round(Wide{weight} * e, df + w.eps_frac - pf, Round::Nearest),
                                  -(Wide{1} << (pf - 1)), (Wide{1} << (pf + w.eps_int - 2)) - 1);
  const PerspReciprocal r = persp_reciprocal(static_cast<int64_t>(x), w);
  const Wide ce = fx::shift_round(c * e, 2 * df + w.eps_frac - pf, Round::Nearest);
  const Wide t = Wide{weight} + fx::shift_round(ce * r.reciprocal, 2 * pf - df + r.shift, Round::Nearest);
  return static_cast<int64_t>(std::clamp<Wide>(t, 0, Wide{1} << df));
}

struct CorrectedFragment {
  CorrectedValue value;
  uint32_t flags = 0;  // the own entry's flags, neighbour_dropped, output_saturated
};

// One pixel: its own entry and, when correct (a design with correction and a
// pixel off its line), the neighbour entry, which lies toward direction. With
// persp the weight is the perspective-correct one (persp_weight).
template <class Int>
inline CorrectedFragment correction_adder_in(const TableEntry& own_entry,
                                             const TableEntry* neighbour_entry, int64_t offset,
                                             int64_t weight, int direction, bool persp,
                                             const Widths& w) {
  CorrectedFragment out;
  out.flags = own_entry.flags;
  const LineValueOf<Int> own = line_value<Int>(own_entry, offset, w);
  LineValueOf<Int> other = own;
  if (neighbour_entry) {
    if (neighbour_entry->flags == 0) {
      other = line_value<Int>(*neighbour_entry, offset, w);
      if (persp) {
        weight = persp_weight(weight, direction, own_entry.eps, w);
        if (own_entry.eps_saturated) out.flags |= flag::kTableSaturated;
      }
    } else {
      out.flags |= flag::kNeighbourDropped;
    }
  }
  out.value = linear_correction(own, other, weight, w);
  if (out.value.saturated) out.flags |= flag::kOutputSaturated;
  return out;
}

// 64-bit arithmetic where the widths allow it (every configuration but the
// widest s_int and fraction bits), 128-bit beyond: the same values.
inline CorrectedFragment correction_adder(const TableEntry& own_entry,
                                          const TableEntry* neighbour_entry, int64_t offset,
                                          int64_t weight, int direction, bool persp,
                                          const Widths& w) {
  return walker_fits_64(w)
             ? correction_adder_in<int64_t>(own_entry, neighbour_entry, offset, weight, direction, persp, w)
             : correction_adder_in<fx::Wide>(own_entry, neighbour_entry, offset, weight, direction, persp, w);
}

}  // namespace cdsim
