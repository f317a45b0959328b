// The one narrow seam between the RTL and the C++ model (STYLE.md): the model
// runs each triangle first; every fragment (x, y, u, v, flags) and every
// per-triangle record (cycles, lines, bands, pixels, flags) the RTL emits is
// compared field by field, and the first mismatch is described with its
// triangle, pixel, field, expected and actual value, and seed.
#pragma once

#include <array>
#include <deque>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "design.hpp"
#include "scan_unit.hpp"
#include "triangle.hpp"
#include "widths.hpp"

namespace cdsim::rtl {

// One triangle at the RTL's input: the unit triangle, the design and viewport.
struct Job {
  UnitTriangle triangle;
  const Design* design = nullptr;
  int viewport_width = 0, viewport_height = 0;
  std::string origin;  // "scene triangle 12", "random 40 (sliver)"
  uint64_t number = 0;  // its index in the whole source: seeds its back-pressure, names it in reports
};

struct RtlFragment {
  int64_t x = 0, y = 0, u = 0, v = 0;
  uint32_t flags = 0;
};

// The setup engine's results as the RTL's observation ports show them.
struct RtlSetup {
  bool empty = true, x_major = true, no_lines = true, depth_range = false;
  int64_t g = 0, major_lo = 0, major_count = 0, minor_lo = 0, minor_hi = 0;
  int64_t pixel_line_lo = 0, pixel_line_hi = 0;
};

// One table write.
struct RtlTableWrite {
  int64_t address = 0, t_u = 0, t_v = 0, s_u = 0, s_v = 0;
  int64_t eps = 0;  // cd-persp (compared only for its triangles: the fill of a unit with it always computes eps)
  bool saturated = false, depth_range = false, eps_saturated = false;
};

struct RtlRecord {
  int64_t cycles = 0, lines = 0, bands = 0, pixels = 0;
  uint32_t flags = 0;
};

// Triangles overlap in the unit (setup_fifo_depth >= 1): the next one is set
// up while the last one's fragments leave, and with a fill stage and two table
// banks (setup_fifo_depth 2, table_banks 2) filled while the last one is
// walked. The scoreboard keeps the triangles accepted and not yet recorded in
// order: fragments and the record belong to the oldest (the back end's),
// table writes to the oldest whose writes are not all seen, setup results to
// the oldest whose setup has not been seen.
class Scoreboard {
 public:
  Scoreboard(const Widths& widths, uint64_t seed) : widths_(widths), seed_(seed), schedule_(widths) {}

  // A unit without the scanline table (HasTable = 0: divide, affine or Kim
  // alone) computes no g and no pixel line range, and its observation ports
  // read 0 there: the setup comparison leaves them out.
  void set_unit_has_table(bool has_table) { unit_has_table_ = has_table; }

  // A triangle accepted by the unit: the model runs it and places it on the
  // unit's schedule; its fragments and record become the expectation.
  void accept(size_t index, const Job& job);
  // Each returns false at a mismatch; mismatch() then describes it.
  bool setup(const RtlSetup& actual);
  bool table_write(const RtlTableWrite& actual);
  bool fragment(const RtlFragment& actual);
  // The oldest triangle's record. stall_cycles: the cycles since the last
  // record in which the sink refused a fragment; the unit held for each, so
  // the RTL counts them and the model does not.
  bool record(const RtlRecord& actual, int64_t stall_cycles);
  // Forgets the triangles in flight and starts a new schedule (a replay from
  // an idle unit).
  void restart();

  const std::string& mismatch() const { return mismatch_; }
  // The triangle of the last mismatch.
  size_t failed_index() const { return failed_index_; }
  size_t in_flight() const { return pending_.size(); }
  int64_t fragments_compared() const { return fragments_compared_; }
  int64_t setups_compared() const { return setups_compared_; }
  int64_t writes_compared() const { return writes_compared_; }
  // The model's clocks of the triangles recorded (their attribution on the
  // schedule), and the RTL's record counts.
  int64_t model_cycles() const { return model_cycles_; }
  int64_t rtl_cycles() const { return rtl_cycles_; }
  int64_t mismatches() const { return mismatches_; }
  // Triangles whose record raised each flag, and banded / y-major triangles:
  // evidence that a width configuration really exercises its corners.
  std::string flag_census() const;
  // Triangles with each flag, by name; y-major triangles.
  std::vector<std::pair<std::string, int64_t>> flag_counts() const;
  int64_t y_major() const { return y_major_; }

 private:
  struct Expected {
    const Job* job = nullptr;
    size_t index = 0;
    std::vector<Fragment> fragments;
    BlockTrace trace;
    TriangleRecord record;
    size_t next_fragment = 0, next_write = 0;
    bool setup_seen = false;
  };
  bool fail(const Expected& e, const std::string& where, const char* field, int64_t expected, int64_t actual);
  bool fail_unexpected(const std::string& what);
  ScanUnit& unit_for(const Job& job);

  Widths widths_;
  uint64_t seed_;
  bool unit_has_table_ = true;
  std::map<std::tuple<std::string, int, int>, std::unique_ptr<ScanUnit>> units_;
  UnitSchedule schedule_;  // one stream through the unit, whatever the designs
  std::deque<Expected> pending_;
  size_t setups_seen_ = 0;  // of the triangles in pending_, from the oldest
  size_t failed_index_ = 0;
  int64_t setups_compared_ = 0, writes_compared_ = 0;
  int64_t fragments_compared_ = 0, model_cycles_ = 0, rtl_cycles_ = 0, mismatches_ = 0;
  std::string mismatch_;
  std::array<int64_t, flag::kCount> flagged_{};
  int64_t y_major_ = 0;
};

std::string describe_job(const Job& job);

// The model unit a job runs on: one per design and viewport, except the
// adaptive design's, one for all viewports (its schedule is the RTL's one
// stream; ScanUnit::set_viewport per triangle).
using UnitKey = std::tuple<std::string, int, int>;
UnitKey unit_key(const Job& job);

}  // namespace cdsim::rtl
