// Column walker: per column (row, when y-major) the offset o, the rounded line
// shift r(o) = round(density g o), the signed distance t to the line and the
// covered span; per pixel the line index and u_line = T_k + o S_k.
#pragma once

#include <cstdint>

#include "pixel_coverage.hpp"
#include "fixed.hpp"
#include "setup_engine.hpp"

namespace cdsim {

struct ColumnState {
  int64_t offset = 0;        // o, columns from the reference column
  int64_t major = 0;         // pixel index along the walked axis
  int64_t line_shift = 0;    // r(o) = round(density * g * o), ties toward +inf
  int direction = 0;         // sign(t): which neighbour line the correction uses
  int64_t weight = 0;        // |t| in d_frac fraction bits (t in line spacings)
  Span span;                 // covered pixels along the column, clipped to the box
};

// The line phase phi in g_frac fraction bits: where m g o starts.
inline int64_t line_phase_g(const Setup& s, const Widths& w) {
  return s.line_phase * (int64_t{1} << (w.g_frac - s.line_phase_bits));
}

// The walker as the hardware runs it: column by column from the first, m g o
// and each edge's span end accumulated (Setup::edge_trackers), no division.
class ColumnWalker {
 public:
  ColumnWalker(const Setup& setup, const Widths& widths) : setup_(setup), widths_(widths) {
    restart();
  }
  void restart();  // column 0: the start of a band
  void advance();  // the next column
  ColumnState column() const;

 private:
  const Setup& setup_;
  const Widths& widths_;
  int64_t offset_ = 0;
  int64_t exact_ = 0;  // m g o + phi in g_frac fraction bits
  std::array<int64_t, 3> bound_{}, remainder_{};
};

// The same column computed directly: covered_span by division. The tests
// check that the walker's spans equal it.
ColumnState walk_column(const Setup& setup, int64_t offset, const Widths& widths);

// The pixels of a column whose line lies in [band_lo, band_hi] (line =
// m (minor - minor_lo) - r), within the column's span.
Span clip_to_band(const Setup& setup, const ColumnState& column, int64_t band_lo, int64_t band_hi);

// Line index of the pixel minor_index in this column.
inline int64_t line_index(const Setup& setup, const ColumnState& column, int64_t minor_index) {
  return setup.density * (minor_index - setup.minor_lo) - column.line_shift;
}

// u_line(k, o) in max(t_frac, s_frac) fraction bits; exact, no narrowing.
// Int is int64_t where walker_bits() allows, else fx::Wide (the widest
// t_int, s_int and fraction bits of widths.def need 74 bits).
template <class Int>
struct LineValueOf {
  Int u = 0, v = 0;
};
using LineValue = LineValueOf<int64_t>;
inline int accumulator_frac(const Widths& w) { return w.t_frac > w.s_frac ? w.t_frac : w.s_frac; }
// Bits of the walker's accumulator T + o S (o up to 2^14 columns), with the
// correction's bit and the output fraction bits beyond it (validate()).
inline int walker_bits(const Widths& w) {
  const int frac = accumulator_frac(w);
  const int t = w.t_int + frac, s = w.s_int + frac + 14;
  return (t > s ? t : s) + 2 + (w.out_frac > frac ? w.out_frac - frac : 0);
}
inline bool walker_fits_64(const Widths& w) { return walker_bits(w) <= 63; }
// The alignment of T and S to the accumulator's fraction bits, computed once
// for a set of widths. Multiplications, not shifts: left-shifting a negative
// value is undefined in C++17.
template <class Int>
struct LineScale {
  Int t_scale, s_scale;
  explicit LineScale(const Widths& w)
      : t_scale(Int{1} << (accumulator_frac(w) - w.t_frac)), s_scale(Int{1} << (accumulator_frac(w) - w.s_frac)) {}
};
template <class Int>
inline LineValueOf<Int> line_value(const TableEntry& e, int64_t offset, const LineScale<Int>& scale) {
  return {Int{e.t_u} * scale.t_scale + Int{offset} * (Int{e.s_u} * scale.s_scale),
          Int{e.t_v} * scale.t_scale + Int{offset} * (Int{e.s_v} * scale.s_scale)};
}
template <class Int = int64_t>
inline LineValueOf<Int> line_value(const TableEntry& e, int64_t offset, const Widths& w) {
  return line_value(e, offset, LineScale<Int>(w));
}

}  // namespace cdsim
