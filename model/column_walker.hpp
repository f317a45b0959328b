// Column walker: per column (row, when y-major) the offset o, the rounded line
// shift r(o) = round(density g o), the signed distance t to the line and the
// covered span; per pixel the line index and u_line = T_k + o S_k.
#pragma once

#include <cstdint>

#include "coverage.hpp"
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
  int64_t exact_ = 0;  // m g o in g_frac fraction bits
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
struct LineValue {
  int64_t u = 0, v = 0;
};
inline int accumulator_frac(const Widths& w) { return w.t_frac > w.s_frac ? w.t_frac : w.s_frac; }
inline LineValue line_value(const TableEntry& e, int64_t offset, const Widths& w) {
  const int frac = accumulator_frac(w);
  const int t_align = frac - w.t_frac, s_align = frac - w.s_frac;
  // Multiplications, not shifts: left-shifting a negative value is undefined in C++17.
  const int64_t t_scale = int64_t{1} << t_align, s_scale = int64_t{1} << s_align;
  return {e.t_u * t_scale + offset * (e.s_u * s_scale), e.t_v * t_scale + offset * (e.s_v * s_scale)};
}

}  // namespace cdsim
