#include "scan_unit.hpp"

#include <algorithm>

#include "column_walker.hpp"
#include "correction_adder.hpp"
#include "divide_datapath.hpp"
#include "setup_engine.hpp"

namespace cdsim {

ScanUnit::ScanUnit(const Design& design, const Widths& widths, int viewport_width,
                   int viewport_height)
    : design_(design),
      widths_(widths),
      viewport_width_(viewport_width),
      viewport_height_(viewport_height),
      table_(widths.table_depth * design.density) {}

TriangleRecord ScanUnit::run(const UnitTriangle& triangle, std::vector<Fragment>* fragments) {
  const Setup setup = setup_engine(triangle, design_, widths_, viewport_width_, viewport_height_);
  TriangleRecord record = setup.empty ? TriangleRecord{}
                          : design_.kind == Design::Kind::Divide
                              ? run_divide(setup, fragments)
                              : run_constant_depth(setup, fragments);
  record.setup_cycles = widths_.setup_cycles;
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
    for (int64_t line = band_lo - guard; line <= band_hi + guard; ++line)
      table_.write(line, fill_line(s, line, widths_));
    const int64_t band_lines = band_hi - band_lo + 1 + 2 * guard;
    record.lines += band_lines;
    record.fill_cycles += band_lines + widths_.recip_latency;

    // Walk: one cycle per column, plus one per pixel emitted in this band.
    record.walk_cycles += s.major_count;
    for (int64_t offset = 0; offset < s.major_count; ++offset) {
      const ColumnState c = walk_column(s, offset, widths_);
      // Pixels of this column whose line lies in the band.
      const int64_t band_first = s.minor_lo + static_cast<int64_t>(fx::ceil_div(band_lo + c.line_shift, s.density));
      const int64_t band_last = s.minor_lo + static_cast<int64_t>(fx::floor_div(band_hi + c.line_shift, s.density));
      const int64_t first = std::max(c.span.lo, band_first);
      const int64_t last = std::min(c.span.hi, band_last);
      for (int64_t minor = first; minor <= last; ++minor) {
        const int64_t line = line_index(s, c, minor);
        const TableEntry& own_entry = table_.read(line);
        const LineValue own = line_value(own_entry, c.offset, widths_);
        uint32_t entry_flags = own_entry.flags;
        LineValue other = own;
        if (s.correction && c.direction != 0) {
          const TableEntry& neighbour = table_.read(line + c.direction);
          if (neighbour.flags == 0)
            other = line_value(neighbour, c.offset, widths_);
          else
            entry_flags |= flag::kNeighbourDropped;
        }
        const CorrectedValue value = correction_adder(own, other, c.weight, widths_);
        fragments->push_back(make_fragment(s, c, minor, value));
        fragments->back().flags |= entry_flags;
        record.flags |= fragments->back().flags;
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
  for (int64_t offset = 0; offset < s.major_count; ++offset) {
    const ColumnState c = walk_column(s, offset, widths_);
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

}  // namespace cdsim
