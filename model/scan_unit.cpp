#include "scan_unit.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <limits>

#include "column_walker.hpp"
#include "correction_adder.hpp"
#include "adaptive_split.hpp"
#include "affine_datapath.hpp"
#include "divide_datapath.hpp"
#include "kim_datapath.hpp"
#include "setup_engine.hpp"

namespace cdsim {

ScanUnit::ScanUnit(const Design& design, const Widths& widths, int viewport_width,
                   int viewport_height)
    : design_(design),
      widths_(widths),
      derived_(derive(widths)),
      viewport_width_(viewport_width),
      viewport_height_(viewport_height),
      table_(widths.table_depth * design.density),
      timing_(design, widths),
      schedule_(widths),
      adaptive_schedule_(widths) {
  if (design.kind == Design::Kind::Adaptive)
    leaf_unit_ = std::make_unique<ScanUnit>(find_design("affine"), adaptive_leaf_widths(widths), viewport_width,
                                            viewport_height);
}

void ScanUnit::set_viewport(int viewport_width, int viewport_height) {
  viewport_width_ = viewport_width;
  viewport_height_ = viewport_height;
  if (leaf_unit_) leaf_unit_->set_viewport(viewport_width, viewport_height);
}

TriangleRecord ScanUnit::run(const UnitTriangle& triangle, std::vector<Fragment>* fragments, int64_t offered) {
  if (design_.kind == Design::Kind::Adaptive) return run_adaptive(triangle, fragments, true);
  TriangleRecord record = compute(triangle, fragments);
  const TriangleCycles c = schedule_.next(phases(), offered);
  record.setup_cycles = c.setup;
  record.fill_cycles = c.fill;
  record.walk_cycles = c.walk;
  record.record_cycles = c.record;
  record.cycles = c.total();
  return record;
}

TriangleRecord ScanUnit::compute(const UnitTriangle& triangle, std::vector<Fragment>* fragments) {
  if (design_.kind == Design::Kind::Adaptive) return run_adaptive(triangle, fragments, false);
  const Setup setup = setup_engine(triangle, design_, widths_, derived_, viewport_width_, viewport_height_);
  if (trace_) {
    trace_->setup = setup;
    trace_->writes.clear();
  }
  work_.clear();
  TriangleRecord record;
  if (!setup.empty) {
    work_.walked = true;
    work_.columns = setup.major_count;
    work_.fallback = setup.fallback;
    switch (setup.fallback ? Design::Kind::Divide : design_.kind) {
      case Design::Kind::ConstantDepth: record = run_constant_depth(setup, fragments); break;
      case Design::Kind::Divide: record = run_divide(setup, fragments); break;
      case Design::Kind::Kim: record = run_kim(setup, fragments); break;
      case Design::Kind::Affine: record = run_affine(triangle, setup, fragments); break;
      case Design::Kind::Adaptive: break;  // run_adaptive
    }
  }
  record.x_major = setup.x_major;
  record.fallback = setup.fallback;
  record.flags |= setup.flags;
  return record;
}

namespace {

int32_t span_pixels(const Span& span) {
  return span.empty() ? 0 : static_cast<int32_t>(span.hi - span.lo + 1);
}

Fragment make_fragment(const Setup& s, const ColumnState& c, int64_t minor,
                       const CorrectedValue& value) {
  Fragment f;
  f.x = static_cast<int32_t>(s.x_major ? c.major : minor);
  f.y = static_cast<int32_t>(s.x_major ? minor : c.major);
  f.u = value.u;
  f.v = value.v;
  f.flags = value.saturated ? flag::kOutputSaturated : 0;
  return f;
}

}  // namespace

// The walk of the designs without a table: every column of the box once, its
// covered span recorded for the timing layer, then `pixel(column, offset)`.
template <class ColumnVisitor>
void ScanUnit::walk_columns(const Setup& s, ColumnVisitor&& visit) {
  ColumnWalker walker(s, widths_);
  for (int64_t offset = 0; offset < s.major_count; ++offset, walker.advance()) {
    const ColumnState c = walker.column();
    work_.column_pixels.push_back(span_pixels(c.span));
    visit(c, offset);
  }
}

// One column's pixels in a band: each reads its own line and, when corrected,
// the neighbour toward direction. Consecutive pixels read lines `density`
// apart, so a line's value T_k + o S_k (fixed for the column) is often the
// previous pixel's other line: it is kept rather than computed again.
template <class Int>
void ScanUnit::walk_column(const Setup& s, const ColumnState& c, const Span& pixels, int64_t band_base,
                           std::vector<Fragment>* fragments, TriangleRecord* record) {
  const int64_t count = span_pixels(pixels);
  if (count == 0) return;
  const bool correct = s.correction && c.direction != 0;
  const LineScale<Int> scale(widths_);
  const CorrectionFormat format(widths_);
  // The bank row read first: the own line, or the neighbour above it.
  const int64_t top_bias = (correct && c.direction > 0 ? 1 : 0) - band_base;
  struct Known {
    int64_t line;
    LineValueOf<Int> value;
  };
  std::array<Known, 2> known{{{std::numeric_limits<int64_t>::min(), {}}, {std::numeric_limits<int64_t>::min(), {}}}};
  const auto value_of = [&](int64_t line, const TableEntry& entry) {
    for (const Known& k : known)
      if (k.line == line) return k.value;
    known[1] = known[0];
    known[0] = {line, line_value<Int>(entry, c.offset, scale)};
    return known[0].value;
  };
  // Grown once per column (geometrically), filled by index: no capacity
  // check per pixel.
  work_.read_tops.resize(work_.read_tops.size() + static_cast<size_t>(count));
  int32_t* top = work_.read_tops.data() + work_.read_tops.size() - count;
  fragments->resize(fragments->size() + static_cast<size_t>(count));
  Fragment* f = fragments->data() + fragments->size() - count;
  // Lines grow with minor (density > 0): the column reads first .. last.
  const int64_t below = correct ? std::min(0, c.direction) : 0, above = correct ? std::max(0, c.direction) : 0;
  const int64_t first = line_index(s, c, pixels.lo) + below;  // line_index: density (minor - minor_lo) - r
  const TableEntry* rows = table_.read_lines(first, line_index(s, c, pixels.hi) + above);
  // Locals: the stores below could alias the setup's and column's fields.
  const int64_t density = s.density, direction = c.direction, weight = c.weight;
  const int64_t line_lo = line_index(s, c, pixels.lo);
  const bool persp = s.persp, x_major = s.x_major;
  const int32_t major = static_cast<int32_t>(c.major);
  uint32_t flags = 0;
  for (int64_t minor = pixels.lo, line = line_lo; minor <= pixels.hi; ++minor, line += density, ++top, ++f) {
    *top = static_cast<int32_t>(line + top_bias);
    const TableEntry& own = rows[line - first];
    const LineValueOf<Int> own_value = value_of(line, own);
    const TableEntry* neighbour = correct ? &rows[line + direction - first] : nullptr;
    const LineValueOf<Int> neighbour_value =
        neighbour && neighbour->flags == 0 ? value_of(line + direction, *neighbour) : own_value;
    const CorrectedFragment out = correct_line_values<Int>(own, own_value, neighbour, neighbour_value, weight,
                                                           static_cast<int>(direction), persp, widths_, format);
    // Field by field: a Fragment assembled on the stack and copied stalls on
    // store forwarding (it was a third of the model's time).
    f->x = x_major ? major : static_cast<int32_t>(minor);
    f->y = x_major ? static_cast<int32_t>(minor) : major;
    f->u = out.value.u;
    f->v = out.value.v;
    f->flags = out.flags;
    flags |= out.flags;
  }
  record->flags |= flags;
  record->pixels += count;
}

TriangleRecord ScanUnit::run_constant_depth(const Setup& s, std::vector<Fragment>* fragments) {
  TriangleRecord record;
  if (s.pixel_line_lo > s.pixel_line_hi) {
    // No pixel centre can be covered: the walker still scans the columns once.
    work_.column_pixels.assign(static_cast<size_t>(s.major_count), 0);
    return record;
  }
  const int64_t guard = s.correction ? 1 : 0;  // correction neighbours above and below
  const int64_t depth = table_.depth();
  const int64_t pixel_lines = s.pixel_line_hi - s.pixel_line_lo + 1;
  const int64_t lines_per_band = pixel_lines + 2 * guard <= depth ? pixel_lines : depth - 2 * guard;
  for (int64_t band_lo = s.pixel_line_lo; band_lo <= s.pixel_line_hi; band_lo += lines_per_band) {
    const int64_t band_hi = std::min(s.pixel_line_hi, band_lo + lines_per_band - 1);
    ++record.bands;
    table_.start_band(band_lo - guard);
    for (int64_t line = band_lo - guard; line <= band_hi + guard; ++line) {
      const TableEntry entry = fill_line(s, line, widths_);
      table_.write(line, entry);
      if (trace_) trace_->writes.push_back({line - (band_lo - guard), entry});
    }
    const int64_t band_lines = band_hi - band_lo + 1 + 2 * guard;
    record.lines += band_lines;
    work_.band_lines.push_back(band_lines);

    // Walk every column, emitting the pixels whose line is in this band.
    ColumnWalker walker(s, widths_);
    for (int64_t offset = 0; offset < s.major_count; ++offset, walker.advance()) {
      const ColumnState c = walker.column();
      const Span pixels = clip_to_band(s, c, band_lo, band_hi);
      work_.column_pixels.push_back(span_pixels(pixels));
      if (walker_fits_64(widths_))
        walk_column<int64_t>(s, c, pixels, band_lo - guard, fragments, &record);
      else
        walk_column<fx::Wide>(s, c, pixels, band_lo - guard, fragments, &record);
    }
  }
  if (record.bands > 1) record.flags |= flag::kBanded;
  return record;
}

TriangleRecord ScanUnit::run_divide(const Setup& s, std::vector<Fragment>* fragments) {
  TriangleRecord record;
  walk_columns(s, [&](const ColumnState& c, int64_t offset) {
    for (int64_t minor = c.span.lo; minor <= c.span.hi; ++minor) {
      const CorrectedValue value = divide_pixel(s, offset, minor - s.minor_lo, widths_, &record.flags);
      fragments->push_back(make_fragment(s, c, minor, value));
      record.flags |= fragments->back().flags;
      ++record.pixels;
    }
  });
  return record;
}

TriangleRecord ScanUnit::run_kim(const Setup& s, std::vector<Fragment>* fragments) {
  TriangleRecord record;
  walk_columns(s, [&](const ColumnState& c, int64_t offset) {
    KimPixel previous;
    for (int64_t minor = c.span.lo; minor <= c.span.hi; ++minor) {
      const bool first = minor == c.span.lo;
      const KimPixel p =
          kim_pixel(s, offset, minor - s.minor_lo, widths_, first ? nullptr : &previous, &record.flags);
      // How far the integer stage steps to this pixel (timing.cpp prices it).
      work_.kim_steps.push_back(first ? 0
                                      : std::max(std::abs(p.integer_u - previous.integer_u),
                                                 std::abs(p.integer_v - previous.integer_v)));
      previous = p;
      fragments->push_back(make_fragment(s, c, minor, p.value));
      record.flags |= fragments->back().flags;
      ++record.pixels;
    }
  });
  return record;
}

TriangleRecord ScanUnit::run_affine(const UnitTriangle& triangle, const Setup& s,
                                    std::vector<Fragment>* fragments) {
  TriangleRecord record;
  const int64_t segment = design_.subdivision;
  const AffinePlanes planes = affine_setup(triangle, s, widths_);
  const fx::Format exact_format = affine_format(widths_);
  walk_columns(s, [&](const ColumnState& c, int64_t offset) {
    if (c.span.empty()) return;
    const int64_t length = c.span.hi - c.span.lo + 1;
    if (segment == 0) {
      for (int64_t minor = c.span.lo; minor <= c.span.hi; ++minor) {
        fragments->push_back(make_fragment(s, c, minor, affine_pixel(planes, offset, minor - s.minor_lo, widths_)));
        record.flags |= fragments->back().flags;
      }
      record.pixels += length;
      return;
    }
    // Subdivided: an exact end point every N pixels, interpolated between.
    const auto exact_at = [&](int64_t minor) {
      return divide_uv(s, offset, minor - s.minor_lo, widths_, exact_format, &record.flags);
    };
    const auto emit = [&](int64_t minor, const CorrectedValue& value) {
      fragments->push_back(make_fragment(s, c, minor, value));
      record.flags |= fragments->back().flags;
      ++record.pixels;
    };
    if (design_.quadratic) {
      // Segments of power-of-two length, exact at both ends and the middle.
      CorrectedValue start = exact_at(c.span.lo);
      if (length == 1) emit(c.span.lo, quadratic_segment(start, start, start, 1, 0, widths_));
      for (int64_t first = c.span.lo; first < c.span.hi;) {
        const int64_t run = quadratic_segment_length(c.span.hi - first, segment);
        const CorrectedValue middle = run > 1 ? exact_at(first + run / 2) : start;
        const CorrectedValue end = exact_at(first + run);
        const int64_t stop = first + run == c.span.hi ? run : run - 1;  // the span's final pixel too
        for (int64_t p = 0; p <= stop; ++p) emit(first + p, quadratic_segment(start, middle, end, run, p, widths_));
        first += run;
        start = end;
      }
      return;
    }
    CorrectedValue start = exact_at(c.span.lo);
    for (int64_t first = c.span.lo; first <= c.span.hi; first += segment) {
      const int64_t last = std::min(first + segment, c.span.hi);
      const int64_t run = last - first;  // pixels from first to last end point
      const CorrectedValue end = run > 0 ? exact_at(last) : start;
      // Pixels first .. last-1 (and the span's final pixel itself).
      const int64_t stop = last == c.span.hi ? last : last - 1;
      for (int64_t minor = first; minor <= stop; ++minor)
        emit(minor, run > 0 ? interpolate_segment(start, end, run, minor - first, widths_)
                            : interpolate_segment(start, start, 1, 0, widths_));
      if (last == c.span.hi) break;
      start = end;
    }
  });
  return record;
}

TriangleRecord ScanUnit::run_adaptive(const UnitTriangle& triangle, std::vector<Fragment>* fragments,
                                      bool timed) {
  // The triangle's own setup checks its input and names its major axis.
  const Setup parent = setup_engine(triangle, design_, widths_, derived_, viewport_width_, viewport_height_);
  const AdaptiveSplit split = adaptive_split(triangle, widths_, viewport_width_, viewport_height_);
  work_.clear();
  TriangleRecord record;
  record.x_major = parent.x_major;
  record.flags = parent.flags | split.flags;
  // The leaves' clocks are the leaf unit's; what they do not cover is the
  // split engine's, counted as setup-bound.
  if (timed) adaptive_schedule_.begin_triangle();
  for (const AdaptiveLeaf& leaf : split.leaves) {
    const TriangleRecord r = timed ? leaf_unit_->run(leaf.triangle, fragments, adaptive_schedule_.offer(leaf.work))
                                   : leaf_unit_->compute(leaf.triangle, fragments);
    record.pixels += r.pixels;
    record.flags |= r.flags;
    record.setup_cycles += r.setup_cycles;
    record.fill_cycles += r.fill_cycles;
    record.walk_cycles += r.walk_cycles;
    record.record_cycles += r.record_cycles;
    if (timed) adaptive_schedule_.accepted(leaf_unit_->schedule().last().accept);
  }
  if (!timed) return record;
  record.cycles = adaptive_schedule_.end_triangle(split.tail, leaf_unit_->schedule().last().record);
  record.setup_cycles += record.cycles - (record.setup_cycles + record.fill_cycles + record.walk_cycles +
                                          record.record_cycles);
  return record;
}

}  // namespace cdsim
