#include "column_walker.hpp"

#include <algorithm>

namespace cdsim {

ColumnState walk_column(const Setup& s, int64_t offset, const Widths& w) {
  ColumnState c;
  c.offset = offset;
  c.major = s.major_lo + offset;
  const int gf = w.g_frac;
  const int64_t exact = s.density * s.g * offset;  // density g o in g_frac fraction bits
  c.line_shift = (exact + (int64_t{1} << (gf - 1))) >> gf;
  // The pixel lies t = r(o) - density g o line spacings below its line.
  const int64_t t = c.line_shift * (int64_t{1} << gf) - exact;
  c.direction = t > 0 ? 1 : (t < 0 ? -1 : 0);
  c.weight = static_cast<int64_t>(fx::shift_round(t < 0 ? -t : t, gf - w.d_frac, fx::Round::Nearest));
  const Span covered = covered_span(s.edges, s.x_major, c.major);
  c.span.lo = std::max(covered.lo, s.minor_lo);
  c.span.hi = std::min(covered.hi, s.minor_hi);
  return c;
}

}  // namespace cdsim
