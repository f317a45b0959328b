// The unit: runs triangles through the four blocks (setup engine, scanline
// table, column walker, correction adder) or a per-pixel datapath, and
// describes each triangle's work for the timing layer (timing.hpp), which
// places it on the unit's clock exactly as docs/microarchitecture.md
// describes. The RTL must match those counts triangle by triangle.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "design.hpp"
#include "scanline_table.hpp"
#include "setup_engine.hpp"
#include "timing.hpp"
#include "triangle.hpp"
#include "widths.hpp"

namespace cdsim {

struct Fragment {
  int32_t x = 0, y = 0;
  int64_t u = 0, v = 0;  // output format (out_int.out_frac)
  uint32_t flags = 0;
};

struct TriangleRecord {
  // The triangle's clocks on the unit's schedule (timing.hpp): from the cycle
  // after the previous triangle's record to its own record, both included;
  // setup-bound + fill-bound + walk + record. 0 from ScanUnit::compute.
  int64_t cycles = 0;
  int64_t setup_cycles = 0, fill_cycles = 0, walk_cycles = 0, record_cycles = 0;
  int64_t lines = 0;   // table entries filled, all bands
  int64_t bands = 0;
  int64_t pixels = 0;
  bool x_major = true;
  bool fallback = false;  // walked by the divide fallback (Design::fallback)
  uint32_t flags = 0;
};

// What the setup engine and the table fill produced for one triangle: the
// values the RTL's observation ports show, so that a mismatch can be traced to
// the block where it starts (sim/scoreboard.cpp).
struct TableWrite {
  int64_t address = 0;  // line - (band's first line - guard)
  TableEntry entry;
};
struct BlockTrace {
  Setup setup;
  std::vector<TableWrite> writes;
};

class ScanUnit {
 public:
  ScanUnit(const Design& design, const Widths& widths, int viewport_width, int viewport_height);

  // Appends the triangle's fragments, in emission order, to *fragments, and
  // returns its record with its clocks as the next triangle of this unit's
  // schedule (the first run() of a ScanUnit is accepted in cycle 0).
  // `offered`: the source offers the triangle from that cycle at the earliest
  // (the adaptive design's split engine; 0: whenever the unit can accept it).
  TriangleRecord run(const UnitTriangle& triangle, std::vector<Fragment>* fragments, int64_t offered = 0);
  // The same values without the timing layer: the record's cycle fields stay
  // 0 and the schedule does not move. work() describes what the triangle asked
  // of the hardware, phases() its phases.
  TriangleRecord compute(const UnitTriangle& triangle, std::vector<Fragment>* fragments);
  const TriangleWork& work() const { return work_; }
  TrianglePhases phases() const { return timing_.phases(work_); }
  const UnitTiming& timing() const { return timing_; }

  // The viewport of the triangles from now on; the schedule goes on (one
  // stream through the unit, whatever each triangle's viewport: the RTL's).
  void set_viewport(int viewport_width, int viewport_height);

  const ScanlineTable& table() const { return table_; }
  // When set, run() records the setup and every table write of the triangle.
  void trace_blocks(BlockTrace* trace) { trace_ = trace; }
  const Design& design() const { return design_; }
  const UnitSchedule& schedule() const { return schedule_; }

 private:
  TriangleRecord run_constant_depth(const struct Setup& setup, std::vector<Fragment>* fragments);
  template <class ColumnVisitor>
  void walk_columns(const struct Setup& setup, ColumnVisitor&& visit);
  template <class Int>
  void walk_column(const struct Setup& setup, const struct ColumnState& column, const struct Span& pixels,
                   int64_t band_base, std::vector<Fragment>* fragments, TriangleRecord* record);
  TriangleRecord run_divide(const struct Setup& setup, std::vector<Fragment>* fragments);
  TriangleRecord run_kim(const struct Setup& setup, std::vector<Fragment>* fragments);
  TriangleRecord run_affine(const UnitTriangle& triangle, const struct Setup& setup,
                            std::vector<Fragment>* fragments);
  // The split engine, then each leaf through leaf_unit_; with `timed` on the
  // split engine's and the leaf unit's clocks (docs/designs.md, "adaptive").
  TriangleRecord run_adaptive(const UnitTriangle& triangle, std::vector<Fragment>* fragments, bool timed);

  Design design_;
  Widths widths_;
  DerivedWidths derived_;  // derive(widths_), once
  int viewport_width_, viewport_height_;
  ScanlineTable table_;
  UnitTiming timing_;
  UnitSchedule schedule_;
  TriangleWork work_;  // of the last triangle
  BlockTrace* trace_ = nullptr;
  // adaptive: the affine unit behind the split engine, the cycle the split
  // engine can accept the next triangle, and the cycle of the last record
  // (-1 at first: the first triangle, accepted in cycle 0, counts from there).
  std::unique_ptr<ScanUnit> leaf_unit_;
  AdaptiveSchedule adaptive_schedule_;  // the adaptive design: its split engine's stream
};

}  // namespace cdsim
