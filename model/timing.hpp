// The timing layer: the only code in the model that knows clock cycles.
//
// The blocks (setup_engine, fill_line, ColumnWalker, correction_adder and the
// per-pixel datapaths) are pure functions of values. ScanUnit (scan_unit.hpp)
// drives them and describes what one triangle asked of the hardware, in
// TriangleWork: the bands and their lines, the pixels of every column walked,
// and for the Kim designs the integer steps of every pixel. UnitTiming prices
// that work in the clock cycles the RTL spends on it (docs/microarchitecture.md,
// "Cycles per triangle"). A caller that needs no cycles (an error sweep) can
// skip it: ScanUnit::compute.
#pragma once

#include <cstdint>
#include <vector>

#include "design.hpp"
#include "widths.hpp"

namespace cdsim {

struct TriangleWork {
  // False when the triangle ended after setup (an empty box or det = 0).
  bool walked = false;
  // Columns of the box along the major axis; the walker passes over all of
  // them once per band (once when there is no band).
  int64_t columns = 0;
  // Constant depth: the lines each band fills, guards included. Empty for the
  // per-pixel designs, and for a box where no pixel line is possible.
  std::vector<int64_t> band_lines;
  // Pixels emitted in each column, pass after pass: columns x max(1, bands).
  std::vector<int32_t> column_pixels;
  // Kim: for each pixel in emission order, how far its integer texel moved
  // from the pixel before it in the span (max of |du|, |dv|); 0 for the
  // first pixel of a span, whose integer part comes from the span division.
  std::vector<int64_t> kim_steps;

  void clear() {
    walked = false;
    columns = 0;
    band_lines.clear();
    column_pixels.clear();
    kim_steps.clear();
  }
};

struct TriangleCycles {
  int64_t setup = 0, fill = 0, walk = 0;
  // The clocks of the triangle's handshakes, outside its record's count: the
  // cycle the unit accepts it (IDLE) and the cycle it offers the record.
  int64_t handshake = 0;
  // What the RTL's record counts: setup + fill + walk.
  int64_t total() const { return setup + fill + walk; }
  // Every clock the triangle holds the unit, handshakes included.
  int64_t clocks() const { return total() + handshake; }
};

class UnitTiming {
 public:
  UnitTiming(const Design& design, const Widths& widths);

  // The cycles of one triangle, from the cycle after it is accepted to the
  // cycle before its record is offered, and its handshake cycles. The unit
  // takes triangles one after another, so a scene's clocks, from the first
  // triangle accepted to the last record delivered, are the sum of its
  // triangles' clocks() (plus the stalls of back-pressure).
  TriangleCycles price(const TriangleWork& work) const;

  int64_t setup_cycles() const { return setup_cycles_; }
  // Accept and record: the unit accepts a triangle only in IDLE, the cycle
  // after the last one's record (rtl/cd_scan_unit.sv).
  static constexpr int64_t kHandshakeCycles = 2;

 private:
  int64_t walk_kim(const TriangleWork& work) const;
  int64_t walk_affine(const TriangleWork& work) const;

  Design design_;
  Widths widths_;
  int64_t setup_cycles_;  // from the setup engine's structure (derived_widths.cpp)
};

}  // namespace cdsim
