// Correction adder: u_line = T_k + o S_k for the pixel's line and its
// neighbour, the paper's linear correction u = u_line(k) + |t| (u_line(k') -
// u_line(k)), then rounding and saturation to the output format, and the
// fragment's flags. A flagged neighbour entry is never used (it would spread a
// bad value): the pixel keeps its own line's value and says so. Twin of
// rtl/correction_adder.sv.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>

#include "column_walker.hpp"
#include "design.hpp"

namespace cdsim {

struct CorrectedValue {
  int64_t u = 0, v = 0;  // output format
  bool saturated = false;
};

// The formats the correction adder works in, computed once for a set of
// widths (the model's pixel loop keeps them in registers).
struct CorrectionFormat {
  int d_frac;      // fraction bits of the weight |d|
  int shift;       // accumulator to output fraction bits
  int64_t out_hi;  // the output format's largest value (its smallest is -out_hi - 1)
  explicit CorrectionFormat(const Widths& w)
      : d_frac(w.d_frac),
        shift(accumulator_frac(w) - w.out_frac),
        out_hi((int64_t{1} << (w.out_int + w.out_frac - 1)) - 1) {}
};

// own + round(weight (other - own) 2^-d_frac), narrowed to the output format.
// Without a neighbour pass the same value twice.
template <class Int>
inline CorrectedValue linear_correction(const LineValueOf<Int>& own, const LineValueOf<Int>& neighbour,
                                        int64_t weight, const CorrectionFormat& f) {
  const auto correct = [&](Int a, Int b) {
    if (a == b) return a;
    if constexpr (std::is_same_v<Int, int64_t>) {
      // Neighbouring lines differ little: the product nearly always fits 64
      // bits, and then rounds as the 128-bit one does (d_frac is 1 .. 24).
      int64_t p;
      if (!__builtin_sub_overflow(b, a, &p) && !__builtin_mul_overflow(weight, p, &p) &&
          !__builtin_add_overflow(p, int64_t{1} << (f.d_frac - 1), &p))
        return a + (p >> f.d_frac);
    }
    return a + static_cast<Int>(fx::shift_round(fx::Wide{weight} * (b - a), f.d_frac,
                                                fx::Round::Nearest));
  };
  CorrectedValue out;
  out.u = fx::narrow_nearest_saturate(correct(own.u, neighbour.u), f.shift, -f.out_hi - 1, f.out_hi, &out.saturated);
  out.v = fx::narrow_nearest_saturate(correct(own.v, neighbour.v), f.shift, -f.out_hi - 1, f.out_hi, &out.saturated);
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
inline int64_t persp_table_entry_of(int64_t i, int persp_frac, int persp_table_log2) {
  const int64_t k = int64_t{1} << persp_table_log2;
  // round(2^pf K / (K + i)), ties up.
  return static_cast<int64_t>(((fx::Wide{k} << (persp_frac + 1)) / (k + i) + 1) / 2);
}
inline int64_t persp_table_entry(int64_t i, const Widths& w) {
  // The table for the last widths asked, kept per thread: two 128-bit
  // divisions a pixel were a tenth of cd-persp's time.
  constexpr int kMaxLog2 = 8;  // widths.def: persp_table_log2 <= 8
  thread_local int frac = -1, log2 = -1;
  thread_local std::array<int64_t, (1 << kMaxLog2) + 1> table{};
  if (w.persp_table_log2 > kMaxLog2 || i < 0 || i > (int64_t{1} << w.persp_table_log2))
    return persp_table_entry_of(i, w.persp_frac, w.persp_table_log2);
  if (frac != w.persp_frac || log2 != w.persp_table_log2) {
    for (int64_t j = 0; j <= (int64_t{1} << w.persp_table_log2); ++j)
      table[static_cast<size_t>(j)] = persp_table_entry_of(j, w.persp_frac, w.persp_table_log2);
    frac = w.persp_frac;
    log2 = w.persp_table_log2;
  }
  return table[static_cast<size_t>(i)];
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
// The same with the entries' line values (line_value at this column) given:
// the model's walk reuses a line's value for the next pixel.
template <class Int>
inline CorrectedFragment correct_line_values(const TableEntry& own_entry, const LineValueOf<Int>& own,
                                             const TableEntry* neighbour_entry,
                                             const LineValueOf<Int>& neighbour, int64_t weight,
                                             int direction, bool persp, const Widths& w,
                                             const CorrectionFormat& format) {
  CorrectedFragment out;
  out.flags = own_entry.flags;
  LineValueOf<Int> other = own;
  if (neighbour_entry) {
    if (neighbour_entry->flags == 0) {
      other = neighbour;
      if (persp) {
        weight = persp_weight(weight, direction, own_entry.eps, w);
        if (own_entry.eps_saturated) out.flags |= flag::kTableSaturated;
      }
    } else {
      out.flags |= flag::kNeighbourDropped;
    }
  }
  out.value = linear_correction(own, other, weight, format);
  if (out.value.saturated) out.flags |= flag::kOutputSaturated;
  return out;
}

template <class Int>
inline CorrectedFragment correction_adder_in(const TableEntry& own_entry,
                                             const TableEntry* neighbour_entry, int64_t offset,
                                             int64_t weight, int direction, bool persp,
                                             const Widths& w) {
  const LineValueOf<Int> own = line_value<Int>(own_entry, offset, w);
  return correct_line_values<Int>(own_entry, own, neighbour_entry,
                                  neighbour_entry && neighbour_entry->flags == 0
                                      ? line_value<Int>(*neighbour_entry, offset, w)
                                      : own,
                                  weight, direction, persp, w, CorrectionFormat(w));
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
