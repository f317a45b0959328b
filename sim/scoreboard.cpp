#include "scoreboard.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace cdsim::rtl {

std::string describe_job(const Job& job) {
  std::string text = fmt::format("{} design {} viewport {}x{}:", job.origin, job.design->name,
                                 job.viewport_width, job.viewport_height);
  for (const UnitVertex& v : job.triangle.vertex)
    text += fmt::format(" (x={} y={} q=0x{:08x} u={} v={})", v.x, v.y, v.q_float, v.u, v.v);
  return text;
}

UnitKey unit_key(const Job& job) {
  const bool adaptive = job.design->kind == Design::Kind::Adaptive;
  return {job.design->name, adaptive ? 0 : job.viewport_width, adaptive ? 0 : job.viewport_height};
}

ScanUnit& Scoreboard::unit_for(const Job& job) {
  auto& unit = units_[unit_key(job)];
  if (!unit)
    unit = std::make_unique<ScanUnit>(*job.design, widths_, job.viewport_width,
                                      job.viewport_height);
  return *unit;
}

void Scoreboard::accept(size_t index, const Job& job) {
  Expected& e = pending_.emplace_back();
  e.job = &job;
  e.index = index;
  ScanUnit& unit = unit_for(job);
  if (job.design->kind == Design::Kind::Adaptive) {
    // Its own unit (rtl/adaptive_unit.sv), on its own two clocks: the split
    // engine's and the leaf unit's, one stream whatever the viewports.
    // Nothing inside it is observed.
    unit.set_viewport(job.viewport_width, job.viewport_height);
    e.record = unit.run(job.triangle, &e.fragments);
    return;
  }
  unit.trace_blocks(&e.trace);
  e.record = unit.compute(job.triangle, &e.fragments);
  unit.trace_blocks(nullptr);
  const TriangleCycles c = schedule_.next(unit.phases());
  e.record.cycles = c.total();
}

void Scoreboard::restart() {
  pending_.clear();
  setups_seen_ = 0;
  schedule_.reset();
  units_.clear();  // the adaptive units keep their schedules
}

bool Scoreboard::fail(const Expected& e, const std::string& where, const char* field,
                      int64_t expected, int64_t actual) {
  ++mismatches_;
  failed_index_ = e.index;
  mismatch_ = fmt::format(
      "MISMATCH seed {} triangle {} {}: field {}: expected {}, actual {}\n  triangle {}",
      seed_, e.index, where, field, expected, actual, describe_job(*e.job));
  return false;
}

bool Scoreboard::fail_unexpected(const std::string& what) {
  ++mismatches_;
  failed_index_ = 0;
  mismatch_ = fmt::format("MISMATCH seed {}: {} with no triangle in the unit", seed_, what);
  return false;
}

bool Scoreboard::setup(const RtlSetup& a) {
  if (setups_seen_ >= pending_.size()) return fail_unexpected("setup results");
  Expected& x = pending_[setups_seen_++];
  const Setup& e = x.trace.setup;
  const std::string where = "setup engine";
  x.setup_seen = true;
  ++setups_compared_;
  if (a.empty != e.empty) return fail(x, where, "empty", e.empty, a.empty);
  if (e.empty) return true;  // nothing else of an empty triangle is used
  if (a.x_major != e.x_major) return fail(x, where, "x_major", e.x_major, a.x_major);
  if (unit_has_table_ && a.g != e.g) return fail(x, where, "g", e.g, a.g);
  if (a.major_lo != e.major_lo) return fail(x, where, "major_lo", e.major_lo, a.major_lo);
  if (a.major_count != e.major_count) return fail(x, where, "major_count", e.major_count, a.major_count);
  if (a.minor_lo != e.minor_lo) return fail(x, where, "minor_lo", e.minor_lo, a.minor_lo);
  if (a.minor_hi != e.minor_hi) return fail(x, where, "minor_hi", e.minor_hi, a.minor_hi);
  const bool depth_range = (e.flags & flag::kDepthRange) != 0;
  if (a.depth_range != depth_range) return fail(x, where, "depth_range", depth_range, a.depth_range);
  if (!unit_has_table_) return true;
  const bool no_lines = e.pixel_line_lo > e.pixel_line_hi;
  if (a.no_lines != no_lines) return fail(x, where, "no_lines", no_lines, a.no_lines);
  if (no_lines) return true;
  if (a.pixel_line_lo != e.pixel_line_lo)
    return fail(x, where, "pixel_line_lo", e.pixel_line_lo, a.pixel_line_lo);
  if (a.pixel_line_hi != e.pixel_line_hi)
    return fail(x, where, "pixel_line_hi", e.pixel_line_hi, a.pixel_line_hi);
  return true;
}

bool Scoreboard::table_write(const RtlTableWrite& a) {
  if (pending_.empty()) return fail_unexpected(fmt::format("a table write at address {}", a.address));
  // The table is filled in triangle order: the write belongs to the oldest
  // triangle whose writes are not all seen (or, past them all, the newest).
  auto it = std::find_if(pending_.begin(), pending_.end(),
                         [](const Expected& e) { return e.next_write < e.trace.writes.size(); });
  Expected& x = it != pending_.end() ? *it : pending_.back();
  const std::vector<TableWrite>& writes = x.trace.writes;
  if (x.next_write >= writes.size())
    return fail(x, fmt::format("table write #{} at address {} (the model writes only {})", x.next_write,
                               a.address, writes.size()),
                "count", static_cast<int64_t>(writes.size()), static_cast<int64_t>(x.next_write + 1));
  const TableWrite& e = writes[x.next_write];
  const size_t index = x.next_write++;
  ++writes_compared_;
  const bool saturated = (e.entry.flags & flag::kTableSaturated) != 0;
  const bool depth_range = (e.entry.flags & flag::kDepthRange) != 0;
  const bool persp = x.job->design->persp;
  if (a.address == e.address && a.t_u == e.entry.t_u && a.t_v == e.entry.t_v &&
      a.s_u == e.entry.s_u && a.s_v == e.entry.s_v && a.saturated == saturated &&
      a.depth_range == depth_range &&
      (!persp || (a.eps == e.entry.eps && a.eps_saturated == e.entry.eps_saturated)))
    return true;
  const std::string where = fmt::format("table write #{} (fill)", index);
  if (a.address != e.address) return fail(x, where, "address", e.address, a.address);
  if (a.t_u != e.entry.t_u) return fail(x, where, "T.u", e.entry.t_u, a.t_u);
  if (a.t_v != e.entry.t_v) return fail(x, where, "T.v", e.entry.t_v, a.t_v);
  if (a.s_u != e.entry.s_u) return fail(x, where, "S.u", e.entry.s_u, a.s_u);
  if (a.s_v != e.entry.s_v) return fail(x, where, "S.v", e.entry.s_v, a.s_v);
  if (a.saturated != saturated) return fail(x, where, "table_saturated", saturated, a.saturated);
  if (a.depth_range != depth_range) return fail(x, where, "depth_range", depth_range, a.depth_range);
  if (a.eps != e.entry.eps) return fail(x, where, "eps", e.entry.eps, a.eps);
  return fail(x, where, "eps_saturated", e.entry.eps_saturated, a.eps_saturated);
}

bool Scoreboard::fragment(const RtlFragment& a) {
  if (pending_.empty()) return fail_unexpected(fmt::format("a fragment at pixel ({}, {})", a.x, a.y));
  Expected& x = pending_.front();
  if (x.next_fragment >= x.fragments.size())
    return fail(x, fmt::format("fragment #{} pixel ({}, {}) (the model emits only {})", x.next_fragment,
                               a.x, a.y, x.fragments.size()),
                "count", static_cast<int64_t>(x.fragments.size()),
                static_cast<int64_t>(x.next_fragment + 1));
  const Fragment& e = x.fragments[x.next_fragment];
  const size_t index = x.next_fragment++;
  ++fragments_compared_;
  if (a.x == e.x && a.y == e.y && a.u == e.u && a.v == e.v && a.flags == e.flags) return true;
  const std::string where = fmt::format("fragment #{} pixel ({}, {})", index, e.x, e.y);
  if (a.x != e.x) return fail(x, where, "x", e.x, a.x);
  if (a.y != e.y) return fail(x, where, "y", e.y, a.y);
  if (a.u != e.u) return fail(x, where, "u", e.u, a.u);
  if (a.v != e.v) return fail(x, where, "v", e.v, a.v);
  return fail(x, where, "flags", e.flags, a.flags);
}

bool Scoreboard::record(const RtlRecord& a, int64_t stall_cycles) {
  if (pending_.empty()) return fail_unexpected("a record");
  const Expected x = std::move(pending_.front());
  pending_.pop_front();
  if (setups_seen_ > 0) --setups_seen_;
  const TriangleRecord& e = x.record;
  for (int bit = 0; bit < flag::kCount; ++bit)
    if (e.flags & (1u << bit)) ++flagged_[static_cast<size_t>(bit)];
  if (!e.x_major) ++y_major_;
  model_cycles_ += e.cycles;
  rtl_cycles_ += a.cycles;
  const std::string where = "record";
  if (!x.setup_seen && x.job->design->kind != Design::Kind::Adaptive)
    return fail(x, where, "setup results observed", 1, 0);
  if (x.next_write != x.trace.writes.size())
    return fail(x, where, "table writes", static_cast<int64_t>(x.trace.writes.size()),
                static_cast<int64_t>(x.next_write));
  if (x.next_fragment != x.fragments.size())
    return fail(x, where, "fragments", static_cast<int64_t>(x.fragments.size()),
                static_cast<int64_t>(x.next_fragment));
  if (a.cycles != e.cycles + stall_cycles)
    return fail(x, fmt::format("record ({} stall cycles)", stall_cycles), "cycles", e.cycles + stall_cycles,
                a.cycles);
  if (a.lines != e.lines) return fail(x, where, "lines", e.lines, a.lines);
  if (a.bands != e.bands) return fail(x, where, "bands", e.bands, a.bands);
  if (a.pixels != e.pixels) return fail(x, where, "pixels", e.pixels, a.pixels);
  if (a.flags != e.flags) return fail(x, where, "flags", e.flags, a.flags);
  return true;
}

std::vector<std::pair<std::string, int64_t>> Scoreboard::flag_counts() const {
  std::vector<std::pair<std::string, int64_t>> out;
  for (int bit = 0; bit < flag::kCount; ++bit)
    out.emplace_back(flag::name(bit), flagged_[static_cast<size_t>(bit)]);
  return out;
}

std::string Scoreboard::flag_census() const {
  std::string text = "flags (triangles):";
  for (int bit = 0; bit < flag::kCount; ++bit)
    text += fmt::format(" {}:{}", flag::name(bit), flagged_[static_cast<size_t>(bit)]);
  return text + fmt::format("; y-major triangles: {}", y_major_);
}

}  // namespace cdsim::rtl
