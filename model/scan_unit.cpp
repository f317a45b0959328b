#include "scan_unit.hpp"

#include <algorithm>
#include <cstdlib>

#include "column_walker.hpp"
#include "derived_widths.hpp"
#include "correction_adder.hpp"
#include "affine_datapath.hpp"
#include "divide_datapath.hpp"
#include "kim_datapath.hpp"
#include "setup_engine.hpp"

namespace cdsim {

ScanUnit::ScanUnit(const Design& design, const Widths& widths, int viewport_width,
                   int viewport_height)
    : design_(design),
      widths_(widths),
      viewport_width_(viewport_width),
      viewport_height_(viewport_height),
      table_(widths.table_depth * design.density),
      setup_cycles_(derive(widths).setup_cycles) {}

TriangleRecord ScanUnit::run(const UnitTriangle& triangle, std::vector<Fragment>* fragments) {
  const Setup setup = setup_engine(triangle, design_, widths_, viewport_width_, viewport_height_);
  if (trace_) {
    trace_->setup = setup;
    trace_->writes.clear();
  }
  TriangleRecord record;
  if (!setup.empty) {
    switch (design_.kind) {
      case Design::Kind::ConstantDepth: record = run_constant_depth(setup, fragments); break;
      case Design::Kind::Divide: record = run_divide(setup, fragments); break;
      case Design::Kind::Kim: record = run_kim(setup, fragments); break;
      case Design::Kind::Affine: record = run_affine(triangle, setup, fragments); break;
    }
  }
  record.setup_cycles = setup_cycles_;
  record.cycles = record.setup_cycles + record.fill_cycles + record.walk_cycles;
  record.x_major = setup.x_major;
  record.flags |= setup.flags;
  return record;
}

namespace {

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

TriangleRecord ScanUnit::run_constant_depth(const Setup& s, std::vector<Fragment>* fragments) {
  TriangleRecord record;
  if (s.pixel_line_lo > s.pixel_line_hi) {
    // No pixel centre can be covered: the walker still scans the columns once.
    record.walk_cycles = s.major_count;
    return record;
  }
  const int64_t guard = s.correction ? 1 : 0;  // correction neighbours above and below
  const int64_t depth = table_.depth();
  const int64_t pixel_lines = s.pixel_line_hi - s.pixel_line_lo + 1;
  const int64_t lines_per_band = pixel_lines + 2 * guard <= depth ? pixel_lines : depth - 2 * guard;
  for (int64_t band_lo = s.pixel_line_lo; band_lo <= s.pixel_line_hi; band_lo += lines_per_band) {
    const int64_t band_hi = std::min(s.pixel_line_hi, band_lo + lines_per_band - 1);
    ++record.bands;
    // Fill: one line enters the reciprocal pipeline per cycle.
    table_.start_band(band_lo - guard);
    for (int64_t line = band_lo - guard; line <= band_hi + guard; ++line) {
      const TableEntry entry = fill_line(s, line, widths_);
      table_.write(line, entry);
      if (trace_) trace_->writes.push_back({line - (band_lo - guard), entry});
    }
    const int64_t band_lines = band_hi - band_lo + 1 + 2 * guard;
    record.lines += band_lines;
    record.fill_cycles += band_lines + widths_.recip_latency;

    // Walk: one cycle per column, plus one per pixel emitted in this band.
    record.walk_cycles += s.major_count;
    ColumnWalker walker(s, widths_);
    for (int64_t offset = 0; offset < s.major_count; ++offset, walker.advance()) {
      const ColumnState c = walker.column();
      const Span pixels = clip_to_band(s, c, band_lo, band_hi);
      for (int64_t minor = pixels.lo; minor <= pixels.hi; ++minor) {
        const int64_t line = line_index(s, c, minor);
        const bool correct = s.correction && c.direction != 0;
        const CorrectedFragment out =
            correction_adder(table_.read(line), correct ? &table_.read(line + c.direction) : nullptr,
                             c.offset, c.weight, widths_);
        fragments->push_back(make_fragment(s, c, minor, out.value));
        fragments->back().flags = out.flags;
        record.flags |= out.flags;
        ++record.pixels;
      }
    }
  }
  record.walk_cycles += record.pixels;
  if (record.bands > 1) record.flags |= flag::kBanded;
  return record;
}

TriangleRecord ScanUnit::run_divide(const Setup& s, std::vector<Fragment>* fragments) {
  TriangleRecord record;
  ColumnWalker walker(s, widths_);
  for (int64_t offset = 0; offset < s.major_count; ++offset, walker.advance()) {
    const ColumnState c = walker.column();
    for (int64_t minor = c.span.lo; minor <= c.span.hi; ++minor) {
      const CorrectedValue value =
          divide_pixel(s, offset, minor - s.minor_lo, widths_, &record.flags);
      fragments->push_back(make_fragment(s, c, minor, value));
      record.flags |= fragments->back().flags;
      ++record.pixels;
    }
  }
  // One cycle per column and per pixel, plus draining the reciprocal pipeline.
  record.walk_cycles = s.major_count + record.pixels + widths_.recip_latency;
  return record;
}

TriangleRecord ScanUnit::run_kim(const Setup& s, std::vector<Fragment>* fragments) {
  TriangleRecord record;
  // Two stages overlap (rtl/kim_datapath.sv): A, the integer stage, and B, the
  // fraction stage. Cycles are counted from the first column cycle (0). Each
  // column takes one walker cycle; for a span with pixels A then divides for
  // out_int cycles, and holds the first pixel's I, R in the cycle after. A
  // hands a finished pixel to B in a cycle where B accepts one and starts the
  // next pixel's steps in that same cycle, so pixel k is ready
  // kim_integer_cycles(steps) cycles after pixel k-1's hand-off. B accepts a
  // pixel kim_frac cycles after the last (iterative: one subtractor) or every
  // cycle (pipelined) and offers its fragment kim_frac cycles after the
  // hand-off. The walker's next column cycle follows the span's last hand-off;
  // at the end the unit waits for B's last fragment.
  const int64_t fraction_cycles = widths_.kim_frac;
  const int64_t accept_gap = design_.pipelined ? 1 : fraction_cycles;
  int64_t next_cycle = 0;      // the walker's next cycle
  int64_t b_accepts = 0;       // the first cycle B can take a pixel
  int64_t last_fragment = -1;  // the cycle B offers its last fragment
  ColumnWalker walker(s, widths_);
  for (int64_t offset = 0; offset < s.major_count; ++offset, walker.advance()) {
    const ColumnState c = walker.column();
    const int64_t column_cycle = next_cycle++;
    if (c.span.empty()) continue;
    int64_t ready = column_cycle + 1 + widths_.out_int;  // after the span division
    int64_t handoff = 0;
    KimPixel previous;
    for (int64_t minor = c.span.lo; minor <= c.span.hi; ++minor) {
      const bool first = minor == c.span.lo;
      const KimPixel p =
          kim_pixel(s, offset, minor - s.minor_lo, widths_, first ? nullptr : &previous, &record.flags);
      if (!first) {
        const int64_t steps = std::max(std::abs(p.integer_u - previous.integer_u),
                                       std::abs(p.integer_v - previous.integer_v));
        ready = handoff + kim_integer_cycles(steps, widths_);
      }
      previous = p;
      handoff = std::max(ready, b_accepts);
      b_accepts = handoff + accept_gap;
      last_fragment = handoff + fraction_cycles;
      fragments->push_back(make_fragment(s, c, minor, p.value));
      record.flags |= fragments->back().flags;
      ++record.pixels;
    }
    next_cycle = handoff + 1;
  }
  record.walk_cycles = std::max(next_cycle, last_fragment + 1);
  return record;
}

TriangleRecord ScanUnit::run_affine(const UnitTriangle& triangle, const Setup& s,
                                    std::vector<Fragment>* fragments) {
  TriangleRecord record;
  record.walk_cycles = s.major_count;
  const int64_t segment = design_.subdivision;
  const AffinePlanes planes = affine_setup(triangle, s, widths_);
  const fx::Format exact_format = affine_format(widths_);
  ColumnWalker walker(s, widths_);
  for (int64_t offset = 0; offset < s.major_count; ++offset, walker.advance()) {
    const ColumnState c = walker.column();
    if (c.span.empty()) continue;
    const int64_t length = c.span.hi - c.span.lo + 1;
    record.walk_cycles += length;
    if (segment == 0) {
      for (int64_t minor = c.span.lo; minor <= c.span.hi; ++minor) {
        fragments->push_back(make_fragment(s, c, minor, affine_pixel(planes, offset, minor - s.minor_lo, widths_)));
        record.flags |= fragments->back().flags;
      }
      record.pixels += length;
      continue;
    }
    // Subdivided: the span waits recip_latency cycles for its first two end
    // points (issued in the column cycle and the next); each later end point is
    // issued as the segment before its own starts, so a segment after the
    // first waits max(0, recip_latency - N) cycles for its end point
    // (rtl/affine_sub_datapath.sv).
    record.walk_cycles += widths_.recip_latency;
    const auto exact_at = [&](int64_t minor) {
      return divide_uv(s, offset, minor - s.minor_lo, widths_, exact_format, &record.flags);
    };
    CorrectedValue start = exact_at(c.span.lo);
    for (int64_t first = c.span.lo; first <= c.span.hi; first += segment) {
      const int64_t last = std::min(first + segment, c.span.hi);
      const int64_t run = last - first;  // pixels from first to last end point
      if (first != c.span.lo) record.walk_cycles += std::max<int64_t>(0, widths_.recip_latency - segment);
      const CorrectedValue end = run > 0 ? exact_at(last) : start;
      // Pixels first .. last-1 (and the span's final pixel itself).
      const int64_t stop = last == c.span.hi ? last : last - 1;
      for (int64_t minor = first; minor <= stop; ++minor) {
        const CorrectedValue value =
            run > 0 ? interpolate_segment(start, end, run, minor - first, widths_)
                    : interpolate_segment(start, start, 1, 0, widths_);
        fragments->push_back(make_fragment(s, c, minor, value));
        record.flags |= fragments->back().flags;
        ++record.pixels;
      }
      if (last == c.span.hi) break;
      start = end;
    }
  }
  return record;
}

}  // namespace cdsim
