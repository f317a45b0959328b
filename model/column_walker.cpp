#include "column_walker.hpp"

#include <algorithm>

namespace cdsim {

namespace {

// r(o), the distance t to the line, direction and weight from m g o.
void line_of(ColumnState& c, int64_t exact, const Widths& w) {
  const int gf = w.g_frac;
  c.line_shift = (exact + (int64_t{1} << (gf - 1))) >> gf;  // round, ties toward +inf
  // The pixel lies t = r(o) - density g o line spacings below its line.
  const int64_t t = c.line_shift * (int64_t{1} << gf) - exact;
  c.direction = t > 0 ? 1 : (t < 0 ? -1 : 0);
  c.weight = static_cast<int64_t>(fx::shift_round(t < 0 ? -t : t, gf - w.d_frac, fx::Round::Nearest));
}

}  // namespace

void ColumnWalker::restart() {
  offset_ = 0;
  exact_ = line_phase_g(setup_, widths_);
  for (size_t i = 0; i < 3; ++i) {
    bound_[i] = setup_.edge_trackers[i].bound;
    remainder_[i] = setup_.edge_trackers[i].remainder;
  }
}

void ColumnWalker::advance() {
  ++offset_;
  exact_ += setup_.density * setup_.g;
  for (size_t i = 0; i < 3; ++i) {
    const EdgeTracker& t = setup_.edge_trackers[i];
    bound_[i] += t.slope;
    remainder_[i] += t.slope_remainder;
    if (remainder_[i] >= t.step) {  // Bresenham's carry
      remainder_[i] -= t.step;
      ++bound_[i];
    }
  }
}

ColumnState ColumnWalker::column() const {
  ColumnState c;
  c.offset = offset_;
  c.major = setup_.major_lo + offset_;
  line_of(c, exact_, widths_);
  c.span.lo = setup_.minor_lo;
  c.span.hi = setup_.minor_hi;
  for (size_t i = 0; i < 3; ++i) {
    switch (setup_.edge_trackers[i].kind) {
      case 1: c.span.lo = std::max(c.span.lo, -bound_[i]); break;
      case 2: c.span.hi = std::min(c.span.hi, bound_[i]); break;
      default:
        if (bound_[i] < 0) c.span = Span{};
    }
    if (c.span.empty()) return c.span = Span{}, c;
  }
  return c;
}

ColumnState walk_column(const Setup& s, int64_t offset, const Widths& w) {
  ColumnState c;
  c.offset = offset;
  c.major = s.major_lo + offset;
  line_of(c, s.density * s.g * offset + line_phase_g(s, w), w);
  const Span covered = covered_span(s.edges, s.x_major, c.major);
  c.span.lo = std::max(covered.lo, s.minor_lo);
  c.span.hi = std::min(covered.hi, s.minor_hi);
  if (c.span.empty()) c.span = Span{};
  return c;
}

Span clip_to_band(const Setup& s, const ColumnState& c, int64_t band_lo, int64_t band_hi) {
  const int64_t band_first = s.minor_lo + static_cast<int64_t>(fx::ceil_div(band_lo + c.line_shift, s.density));
  const int64_t band_last = s.minor_lo + static_cast<int64_t>(fx::floor_div(band_hi + c.line_shift, s.density));
  return Span{std::max(c.span.lo, band_first), std::min(c.span.hi, band_last)};
}

}  // namespace cdsim
