// The timing layer: the only code in the model that knows clock cycles.
//
// The blocks (setup_engine, fill_line, ColumnWalker, correction_adder and the
// per-pixel datapaths) are pure functions of values. ScanUnit (scan_unit.hpp)
// drives them and describes what one triangle asked of the hardware, in
// TriangleWork: the bands and their lines, the pixels of every column walked,
// and for the Kim designs the integer steps of every pixel. UnitTiming turns
// that work into the triangle's phases, TrianglePhases: the cycles each band
// fills the table and walks, or the cycles one walk takes; a pure function of
// the work. UnitSchedule places the phases of a stream of triangles on the
// unit's clock: the setup engine, the fill (with setup_fifo_depth 2 a stage
// of its own that holds a triangle) and the back end (column walker and
// datapath) each hold one triangle at a time, and the table's banks hold a
// band each (docs/microarchitecture.md, "Cycles per triangle"). The adaptive
// design's split engine records its work between leaves (SplitEngineWork:
// evaluations, dropped nodes) and AdaptiveSchedule places it, in front of
// its affine unit's own UnitSchedule. A caller that needs no cycles (an error
// sweep) can skip them all: ScanUnit::compute.
//
// Attribution: a triangle's clocks are those from the cycle after the previous
// triangle's record to its own record cycle, both included (the first
// triangle's from its accept cycle). A scene's clocks, from the first accept to
// the last record, both included, are the sum of its triangles' clocks (no
// back-pressure).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "derived_widths.hpp"
#include "design.hpp"
#include "widths.hpp"

namespace cdsim {

struct TriangleWork {
  // False when the triangle ended after setup (an empty box or det = 0).
  bool walked = false;
  // A constant-depth triangle its design sent to the divide fallback: walked
  // as a divide triangle.
  bool fallback = false;
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
  // Constant depth: for each pixel in emission order, the highest table
  // address (line - band base, guards included) its read touches: its own
  // line's, or its correction neighbour's when that lies above.
  std::vector<int32_t> read_tops;

  void clear() {
    walked = false;
    fallback = false;
    columns = 0;
    band_lines.clear();
    column_pixels.clear();
    kim_steps.clear();
    read_tops.clear();
  }
};

// What one triangle asks of the unit's clock, apart from its setup
// (setup_cycles, the same for every triangle).
struct TrianglePhases {
  enum class Kind {
    Empty,  // ended after setup (an empty box or det = 0)
    Scan,   // constant depth with no possible pixel line: one pass over the columns
    Walk,   // a per-pixel design (divide, Kim, affine): one walk, no table
    Bands,  // constant depth: per band, fill the table, then walk every column
  };
  struct Band {
    int64_t fill = 0;  // the band's lines + recip_latency
    int64_t walk = 0;  // columns + the pixels of the band's pass
    // early_walk: the walk reads no line before it is written, and ends no
    // sooner than the cycle after its last fill cycle, if it starts at least
    // this many cycles after the band's first fill cycle; else it stalls the
    // difference. The max of fill - walk + 1 and, over its reads,
    // recip_latency + 1 + the read's top address - the pass cycle it is
    // issued in.
    int64_t read_lag = 0;
  };
  Kind kind = Kind::Empty;
  int64_t scan = 0;          // Scan: one cycle per column
  int64_t walk = 0;          // Walk: the walker and the datapath, drain included
  std::vector<Band> bands;   // Bands: in fill order
  // Bands: after the last band's walk, the correction adder's pipeline
  // registers empty (correction_stages cycles) before the record.
  int64_t drain = 0;
};

// A triangle's clocks (the attribution above), by what bound them.
struct TriangleCycles {
  // The back end idle, waiting for this triangle to be set up (and, at
  // setup_fifo_depth 2, to pass the fill stage); the accept cycle is in it.
  int64_t setup = 0;
  // The back end waiting for each band to be in the table, the band's load
  // cycle included (constant depth).
  int64_t fill = 0;
  // Walking the columns, and for a per-pixel design at setup_fifo_depth 1 or
  // 2 the cycle that loads the walker from its context.
  int64_t walk = 0;
  // The cycle the record is offered.
  int64_t record = 0;
  int64_t total() const { return setup + fill + walk + record; }
};

class UnitTiming {
 public:
  UnitTiming(const Design& design, const Widths& widths) : UnitTiming(design, widths, derive(widths)) {}

  // The phases of one triangle's work.
  TrianglePhases phases(const TriangleWork& work) const;

  int64_t setup_cycles() const { return setup_cycles_; }

 private:
  int64_t walk_kim(const TriangleWork& work) const;
  int64_t walk_affine(const TriangleWork& work) const;

  Design design_;
  Widths widths_;
  int64_t setup_cycles_;  // from the setup engine's structure (derived_widths.cpp)
  int64_t fill_latency_;  // a line's issue to its table write (derived_widths.cpp)
  UnitTiming(const Design& design, const Widths& widths, const DerivedWidths& derived);
};

// The cycle numbers of one triangle on the unit's clock.
struct ScheduledTriangle {
  int64_t accept = 0;  // the front end accepts it
  int64_t taken = 0;   // the back end takes it, its setup done
  int64_t record = 0;  // its record is offered
};

// One stream of triangles through one unit (one design, or a regress stream
// of designs in turn), with no back-pressure. Exactly the RTL's rules
// (rtl/cd_scan_unit.sv, docs/microarchitecture.md):
// - The setup engine accepts a triangle, sets it up in setup_cycles and
//   offers it from its last setup cycle.
// - setup_fifo_depth 0 and 1: the back end takes it then or, if later, in the
//   previous triangle's record cycle. A constant-depth triangle's bands are
//   filled from the setup engine's registers, so the setup engine accepts the
//   next triangle in the cycle the back end takes this one or, when it has
//   bands, in its last band's last fill cycle; at depth 0 only after the
//   previous record (setup, fill and walk in turn).
// - setup_fifo_depth 2: the fill stage takes it (with a copy of everything)
//   when free, the setup engine accepts the next triangle in that cycle, and
//   the back end takes it from the fill stage one cycle later at the earliest.
//   The fill stage is free once the back end has its triangle and its last
//   band is filled.
// - Each band is filled into the next of table_banks banks once the band
//   before in that bank has been walked, and walked from the cycle after its
//   last fill cycle; with early_walk from the cycle after its first, the
//   walk stalling until each line it reads is written.
class UnitSchedule {
 public:
  explicit UnitSchedule(const Widths& widths);

  // Places the next triangle of the stream and returns its clocks. The
  // source offers it from cycle `offered` at the earliest (the split engine
  // of the adaptive design; 0: as soon as the unit can accept it).
  TriangleCycles next(const TrianglePhases& phases, int64_t offered = 0);
  // The cycle numbers of the triangle next() placed last.
  const ScheduledTriangle& last() const { return last_; }
  // Starts a new stream: the next triangle is accepted in cycle 0.
  void reset();
  // The source offers each triangle only from the cycle the previous one's
  // record is delivered (the vector bench, tests/vectors), not as soon as the
  // previous one is accepted (the regress bench, the default).
  void offer_after_record(bool on) { offer_after_record_ = on; }

 private:
  int64_t setup_cycles_;
  int64_t fifo_depth_;
  int64_t banks_;
  bool early_walk_;
  bool offer_after_record_ = false;
  int64_t front_free_ = 0;  // first cycle the setup engine may accept a triangle
  int64_t slot_free_ = 0;   // first cycle the fill stage may take one (depth 2)
  int64_t back_free_ = 0;   // first cycle the back end may take a triangle
  int64_t bands_ = 0;       // bands filled so far: band k goes to bank k % banks
  std::array<int64_t, 2> band_done_{-1, -1};  // per bank: the last walk cycle of its last band
  bool started_ = false;    // a triangle has been placed, so last_.record holds
  ScheduledTriangle last_;
};

// The adaptive design's split engine (rtl/adaptive_split.sv, docs/designs.md):
// what it does between two leaves it hands on, which model/adaptive_split.cpp
// records and these clocks price: the intake of a triangle (1/w normalised,
// U = u q and V = v q), one node's evaluation (the midpoints: three
// reciprocals issued on one pipelined unit, each result multiplied and
// narrowed in the cycle it arrives; the tests), and dropping a node with an
// empty box.
struct SplitEngineWork {
  int64_t evaluations = 0;
  int64_t drops = 0;
};
inline constexpr int64_t kAdaptiveIntakeCycles = 2;
inline constexpr int64_t kAdaptiveDropCycles = 1;
inline int64_t adaptive_evaluation_cycles(const Widths& widths) { return 1 + 3 + widths.recip_latency + 1; }
inline int64_t split_engine_cycles(const SplitEngineWork& work, const Widths& widths) {
  return work.evaluations * adaptive_evaluation_cycles(widths) + work.drops * kAdaptiveDropCycles;
}

// The adaptive design's stream (rtl/adaptive_unit.sv): the split engine
// takes a triangle when it is free, offers each leaf to its affine unit (which
// has its own UnitSchedule) after the engine's work for it, and goes on in the
// cycle after the leaf is accepted.
class AdaptiveSchedule {
 public:
  explicit AdaptiveSchedule(const Widths& widths) : widths_(widths) {}
  // The engine accepts the next triangle; its root node starts after the intake.
  void begin_triangle() { cycle_ = split_free_ + kAdaptiveIntakeCycles; }
  // The cycle the next leaf is offered, `work` after the previous acceptance.
  int64_t offer(const SplitEngineWork& work) { return cycle_ += split_engine_cycles(work, widths_); }
  // The leaf unit accepted the leaf in `accept`.
  void accepted(int64_t accept) { cycle_ = accept + 1; }
  // The triangle ends after `tail` (nodes dropped after its last leaf); its
  // last leaf's record was delivered in `leaf_record`. The engine is free in
  // the cycle after its last node; the triangle's record comes with its last
  // leaf's record or then, whichever is later. Returns its clocks: from the
  // cycle after the previous triangle's record (the first triangle's from
  // its acceptance) to its own.
  int64_t end_triangle(const SplitEngineWork& tail, int64_t leaf_record);

 private:
  Widths widths_;
  int64_t split_free_ = 0, last_record_ = -1, cycle_ = 0;
};

// quad-subN: the cycle of a span's last pixel, counted from its column cycle
// (0), without back-pressure (model/timing.cpp).
int64_t quadratic_span_cycles(int64_t span, int64_t segment, int64_t latency);

}  // namespace cdsim
