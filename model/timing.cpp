#include "timing.hpp"

#include <algorithm>
#include <cstddef>
#include <numeric>

#include "affine_datapath.hpp"
#include "derived_widths.hpp"
#include "kim_datapath.hpp"

namespace cdsim {

namespace {
// Cycles of Kim's integer stage for a pixel whose I moved by `steps` (the
// datapath records the steps: TriangleWork::kim_steps):
// max(1, ceil(steps / kim_unroll)).
int64_t kim_integer_cycles(int64_t steps, const Widths& w) {
  const int64_t per_cycle = w.kim_unroll;
  return steps <= per_cycle ? 1 : (steps + per_cycle - 1) / per_cycle;
}
}  // namespace

UnitTiming::UnitTiming(const Design& design, const Widths& widths, const DerivedWidths& derived)
    : design_(design), widths_(widths), setup_cycles_(derived.setup_cycles), fill_latency_(derived.fill_latency) {}

namespace {

// The cycles of one pass over the columns (rtl/cd_scan_unit.sv, StColumn and
// StPixel) for the designs whose walker loads spans ahead: one cycle per
// pixel, and a column cycle for each column the walker evaluates on its own.
// The walker runs a column ahead of the span: in each pixel cycle but the
// span's last it passes over a column without pixels (not the last column);
// in the span's last pixel cycle it loads the next span if its column has
// pixels, ends the pass if it stands on the last column without any, and
// otherwise hands over to column cycles, one per column, until a column with
// pixels (loaded in its column cycle) or the last column.
//
// pixel(cycle) is called for each pixel in emission order with the pass cycle
// (0 = the first column cycle) in which it moves on; its table read is issued
// the cycle before, as its span is loaded or as the pixel before it moves.
template <typename PixelCycle>
int64_t pass_cycles(std::vector<int32_t>::const_iterator first, std::vector<int32_t>::const_iterator last,
                    PixelCycle&& pixel) {
  const auto columns = static_cast<size_t>(last - first);
  auto pixels = [&](size_t c) { return static_cast<int64_t>(first[static_cast<std::ptrdiff_t>(c)]); };
  int64_t cycles = 0;
  size_t column = 0;
  while (column < columns) {
    ++cycles;  // a column cycle
    if (pixels(column) == 0) {
      ++column;
      continue;
    }
    size_t span = column;
    while (true) {
      for (int64_t i = 0; i < pixels(span); ++i) pixel(cycles + i);
      cycles += pixels(span);
      if (span + 1 == columns) return cycles;
      size_t walker = span + 1;
      for (int64_t skips = pixels(span) - 1; skips > 0 && pixels(walker) == 0 && walker + 1 < columns; --skips)
        ++walker;
      if (pixels(walker) > 0) {
        span = walker;
        continue;
      }
      if (walker + 1 == columns) return cycles;
      column = walker;
      break;
    }
  }
  return cycles;
}

int64_t pass_cycles(std::vector<int32_t>::const_iterator first, std::vector<int32_t>::const_iterator last) {
  return pass_cycles(first, last, [](int64_t) {});
}

}  // namespace

TrianglePhases UnitTiming::phases(const TriangleWork& work) const {
  TrianglePhases p;
  if (!work.walked) return p;
  switch (work.fallback ? Design::Kind::Divide : design_.kind) {
    case Design::Kind::ConstantDepth: {
      if (work.band_lines.empty()) {
        // No possible pixel line: the walker still passes over the columns once.
        p.kind = TrianglePhases::Kind::Scan;
        p.scan = work.columns;
        break;
      }
      // Fill: one line per cycle into the reciprocal pipeline, drained per band.
      // Walk: the band's pass over the columns.
      p.kind = TrianglePhases::Kind::Bands;
      // A read of top address A issued in pass cycle c waits for the line
      // written in the band's fill cycle fill_latency + A (read_lag), and
      // the pass's last cycle, which frees the bank, for the band's last line.
      const auto columns = static_cast<std::ptrdiff_t>(work.columns);
      auto top = work.read_tops.begin();
      for (size_t band = 0; band < work.band_lines.size(); ++band) {
        const auto pass = work.column_pixels.begin() + static_cast<std::ptrdiff_t>(band) * columns;
        TrianglePhases::Band b;
        b.fill = work.band_lines[band] + fill_latency_;
        b.walk = pass_cycles(pass, pass + columns, [&](int64_t cycle) {
          b.read_lag = std::max(b.read_lag, fill_latency_ + 1 + *top++ - (cycle - 1));
        });
        b.read_lag = std::max(b.read_lag, b.fill - b.walk + 1);
        p.bands.push_back(b);
      }
      p.drain = widths_.correction_stages;
      break;
    }
    case Design::Kind::Divide:
      // The pass, plus draining the reciprocal pipeline.
      p.kind = TrianglePhases::Kind::Walk;
      p.walk = pass_cycles(work.column_pixels.begin(), work.column_pixels.end()) + widths_.recip_latency;
      break;
    case Design::Kind::Kim:
      p.kind = TrianglePhases::Kind::Walk;
      p.walk = walk_kim(work);
      break;
    case Design::Kind::Affine:
      p.kind = TrianglePhases::Kind::Walk;
      p.walk = walk_affine(work);
      break;
    case Design::Kind::Adaptive:
      // Its leaves go through an affine unit of their own (ScanUnit::run_adaptive).
      break;
  }
  return p;
}

UnitSchedule::UnitSchedule(const Widths& widths)
    : setup_cycles_(derive(widths).setup_cycles),
      fifo_depth_(widths.setup_fifo_depth),
      banks_(widths.table_banks),
      early_walk_(widths.early_walk != 0) {}

void UnitSchedule::reset() {
  front_free_ = 0;
  slot_free_ = 0;
  back_free_ = 0;
  bands_ = 0;
  band_done_.fill(-1);
  started_ = false;
  last_ = ScheduledTriangle{};
}

TriangleCycles UnitSchedule::next(const TrianglePhases& phases, int64_t offered_from) {
  int64_t accept = std::max(front_free_, offered_from);
  if (fifo_depth_ == 0 && started_) accept = std::max(accept, last_.record + 1);
  if (offer_after_record_ && started_) accept = std::max(accept, last_.record);
  const int64_t offered = accept + setup_cycles_;  // the last setup cycle (after the accept cycle): offered from here
  // With the fill stage (depth 2) the triangle moves into it first, and the
  // back end takes it from there one cycle later at the earliest.
  const int64_t staged = fifo_depth_ > 1 ? std::max(offered, slot_free_) : offered;
  const int64_t taken = std::max(fifo_depth_ > 1 ? staged + 1 : staged, back_free_);
  TriangleCycles c;
  int64_t record = taken + 1;
  int64_t fill_end = -1;  // the last band's last fill cycle
  switch (phases.kind) {
    case TrianglePhases::Kind::Empty: break;
    case TrianglePhases::Kind::Scan:
      c.walk = phases.scan;
      record = taken + phases.scan + 1;
      break;
    case TrianglePhases::Kind::Walk:
      // Overlapped, the walker loads its context in one cycle of its own.
      c.walk = phases.walk + (fifo_depth_ > 0 ? 1 : 0);
      record = taken + c.walk + 1;
      break;
    case TrianglePhases::Kind::Bands: {
      // The fill stage decides in `decided` (the cycle it starts the triangle,
      // or the previous band's last fill cycle) and fills from the next cycle,
      // once its bank's previous band has been walked. The back end waits for
      // each band from `waits` and walks it from the cycle after its last fill
      // cycle, or with early_walk after its first, stalling where a read
      // waits for its line (never without early_walk: read_lag <= fill).
      int64_t decided = fifo_depth_ > 1 ? staged : taken;
      int64_t waits = taken + 1;
      for (const TrianglePhases::Band& band : phases.bands) {
        int64_t& bank_done = band_done_[static_cast<size_t>(bands_++ % banks_)];
        const int64_t fill_start = std::max(decided, bank_done) + 1;
        const int64_t fill_last = fill_start + band.fill - 1;
        const int64_t walk_start = std::max(waits, early_walk_ ? fill_start : fill_last) + 1;
        const int64_t stalls = std::max<int64_t>(0, fill_start + band.read_lag - walk_start);
        bank_done = walk_start + stalls + band.walk - 1;
        c.fill += walk_start - waits + stalls;
        c.walk += band.walk;
        decided = fill_last;
        waits = bank_done + 1;
      }
      fill_end = decided;
      c.walk += phases.drain;
      record = waits + phases.drain;
      break;
    }
  }
  // The back end waited from the cycle after the previous record (the first
  // triangle: from its accept) to the cycle it took this triangle.
  c.setup = started_ ? taken - last_.record : taken - accept + 1;
  c.record = 1;
  // The setup engine is free again in the cycle its triangle leaves it: into
  // the fill stage (depth 2), or to the back end, or, when the table is
  // filled from the setup engine's registers (depth 0 and 1), at the last
  // band's last fill cycle. The fill stage is free once the back end has taken
  // its triangle and its last band is filled.
  if (fifo_depth_ > 1) {
    front_free_ = staged;
    slot_free_ = std::max(taken, fill_end);
  } else {
    front_free_ = phases.kind == TrianglePhases::Kind::Bands ? fill_end : taken;
  }
  back_free_ = record;
  last_ = {accept, taken, record};
  started_ = true;
  return c;
}

// Two stages overlap (rtl/kim_datapath.sv): A, the integer stage, and B, the
// fraction stage. Cycles are counted from the first column cycle (0). Each
// column takes one walker cycle; for a span with pixels A then divides for
// out_int cycles, and holds the first pixel's I, R in the cycle after. A hands
// a finished pixel to B in a cycle where B accepts one and starts the next
// pixel's steps in that same cycle, so pixel k is ready kim_integer_cycles(steps)
// cycles after pixel k-1's hand-off. B accepts a pixel kim_frac cycles after
// the last (iterative: one subtractor) or every cycle (pipelined) and offers
// its fragment kim_frac cycles after the hand-off. The walker's next column
// cycle follows the span's last hand-off; at the end the unit waits for B's
// last fragment.
int64_t UnitTiming::walk_kim(const TriangleWork& work) const {
  const int64_t fraction_cycles = widths_.kim_frac;
  const int64_t accept_gap = design_.pipelined ? 1 : fraction_cycles;
  int64_t next_cycle = 0;      // the walker's next cycle
  int64_t b_accepts = 0;       // the first cycle B can take a pixel
  int64_t last_fragment = -1;  // the cycle B offers its last fragment
  size_t pixel = 0;
  for (const int32_t span : work.column_pixels) {
    const int64_t column_cycle = next_cycle++;
    if (span == 0) continue;
    int64_t ready = column_cycle + 1 + widths_.out_int;  // after the span division
    int64_t handoff = 0;
    for (int32_t i = 0; i < span; ++i, ++pixel) {
      if (i > 0) ready = handoff + kim_integer_cycles(work.kim_steps.at(pixel), widths_);
      handoff = std::max(ready, b_accepts);
      b_accepts = handoff + accept_gap;
      last_fragment = handoff + fraction_cycles;
    }
    next_cycle = handoff + 1;
  }
  return std::max(next_cycle, last_fragment + 1);
}

// quad-subN (rtl/quad_sub_datapath.sv): the cycles after a span's column cycle
// up to its last pixel's. Counting from the column cycle (0), which issues the
// exact point at the span's first pixel: the points are issued in order, one
// per cycle, a segment's (its middle, then its end) no earlier than the cycle
// the segment before it takes its first pixel; a point arrives recip_latency
// cycles after its issue, and a segment's pixels, one per cycle, wait for its
// end point.
int64_t quadratic_span_cycles(int64_t span, int64_t segment, int64_t latency) {
  const int64_t last = span - 1;
  int64_t issued = 0, allowed = 0, taken = 0;
  if (last == 0) return std::max<int64_t>(1, latency);
  for (int64_t first = 0; first < last;) {
    const int64_t run = quadratic_segment_length(last - first, segment);
    if (run > 1) issued = std::max(issued + 1, allowed);  // the middle
    issued = std::max(issued + 1, allowed);               // the end
    const int64_t pixels = first + run == last ? run + 1 : run;
    const int64_t first_take = std::max(taken + 1, issued + latency);
    allowed = first_take;
    taken = first_take + pixels - 1;
    first += run;
  }
  return taken;
}

// Plain affine: the pass over the columns (pass_cycles). Subdivided
// (affine-subN): one cycle per column and per pixel, and a span waits
// recip_latency cycles for its first two end points (issued in the column
// cycle and the next); each later end point is issued as the segment before
// its own starts, so a segment after the first waits
// max(0, recip_latency - N) cycles for its end point (rtl/affine_sub_datapath.sv).
int64_t UnitTiming::walk_affine(const TriangleWork& work) const {
  const int64_t segment = design_.subdivision;
  if (segment == 0) return pass_cycles(work.column_pixels.begin(), work.column_pixels.end());
  if (design_.quadratic) {
    int64_t cycles = work.columns;
    for (const int32_t span : work.column_pixels)
      if (span > 0) cycles += quadratic_span_cycles(span, segment, widths_.recip_latency);
    return cycles;
  }
  int64_t cycles = work.columns;
  for (const int32_t span : work.column_pixels) {
    if (span == 0) continue;
    cycles += span;
    if (segment == 0) continue;
    // Segments of the span: the first ends min(N, span - 1) pixels on, each
    // later one N pixels on, the last at the span's final pixel.
    const int64_t segments = std::max<int64_t>(1, (span - 1 + segment - 1) / segment);
    cycles += widths_.recip_latency + (segments - 1) * std::max<int64_t>(0, widths_.recip_latency - segment);
  }
  return cycles;
}

int64_t AdaptiveSchedule::end_triangle(const SplitEngineWork& tail, int64_t leaf_record) {
  split_free_ = cycle_ + split_engine_cycles(tail, widths_);
  const int64_t recorded = std::max(leaf_record, split_free_);
  const int64_t clocks = recorded - last_record_;
  last_record_ = recorded;
  return clocks;
}

}  // namespace cdsim
