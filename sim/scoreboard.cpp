#include "scoreboard.hpp"

#include <fmt/format.h>

namespace cdsim::rtl {

std::string describe_job(const Job& job) {
  std::string text = fmt::format("{} design {} viewport {}x{}:", job.origin, job.design->name,
                                 job.viewport_width, job.viewport_height);
  for (const UnitVertex& v : job.triangle.vertex)
    text += fmt::format(" (x={} y={} q=0x{:08x} u={} v={})", v.x, v.y, v.q_float, v.u, v.v);
  return text;
}

ScanUnit& Scoreboard::unit_for(const Job& job) {
  auto key = std::make_tuple(job.design->name, job.viewport_width, job.viewport_height);
  auto& unit = units_[key];
  if (!unit)
    unit = std::make_unique<ScanUnit>(*job.design, widths_, job.viewport_width,
                                      job.viewport_height);
  return *unit;
}

void Scoreboard::begin(size_t index, const Job& job) {
  job_ = &job;
  index_ = index;
  expected_.clear();
  next_ = 0;
  next_write_ = 0;
  setup_seen_ = false;
  ScanUnit& unit = unit_for(job);
  unit.trace_blocks(&trace_);
  expected_record_ = unit.run(job.triangle, &expected_);
}

bool Scoreboard::fail(const std::string& where, const char* field, int64_t expected,
                      int64_t actual) {
  ++mismatches_;
  mismatch_ = fmt::format(
      "MISMATCH seed {} triangle {} {}: field {}: expected {}, actual {}\n  triangle {}",
      seed_, index_, where, field, expected, actual, describe_job(*job_));
  return false;
}

bool Scoreboard::setup(const RtlSetup& a) {
  const Setup& e = trace_.setup;
  const std::string where = "setup engine";
  setup_seen_ = true;
  ++setups_compared_;
  if (a.empty != e.empty) return fail(where, "empty", e.empty, a.empty);
  if (e.empty) return true;  // nothing else of an empty triangle is used
  if (a.x_major != e.x_major) return fail(where, "x_major", e.x_major, a.x_major);
  if (a.g != e.g) return fail(where, "g", e.g, a.g);
  if (a.major_lo != e.major_lo) return fail(where, "major_lo", e.major_lo, a.major_lo);
  if (a.major_count != e.major_count) return fail(where, "major_count", e.major_count, a.major_count);
  if (a.minor_lo != e.minor_lo) return fail(where, "minor_lo", e.minor_lo, a.minor_lo);
  if (a.minor_hi != e.minor_hi) return fail(where, "minor_hi", e.minor_hi, a.minor_hi);
  const bool depth_range = (e.flags & flag::kDepthRange) != 0;
  if (a.depth_range != depth_range) return fail(where, "depth_range", depth_range, a.depth_range);
  const bool no_lines = e.pixel_line_lo > e.pixel_line_hi;
  if (a.no_lines != no_lines) return fail(where, "no_lines", no_lines, a.no_lines);
  if (no_lines) return true;
  if (a.pixel_line_lo != e.pixel_line_lo)
    return fail(where, "pixel_line_lo", e.pixel_line_lo, a.pixel_line_lo);
  if (a.pixel_line_hi != e.pixel_line_hi)
    return fail(where, "pixel_line_hi", e.pixel_line_hi, a.pixel_line_hi);
  return true;
}

bool Scoreboard::table_write(const RtlTableWrite& a) {
  if (next_write_ >= trace_.writes.size())
    return fail(fmt::format("table write #{} at address {} (the model writes only {})", next_write_,
                            a.address, trace_.writes.size()),
                "count", static_cast<int64_t>(trace_.writes.size()),
                static_cast<int64_t>(next_write_ + 1));
  const TableWrite& e = trace_.writes[next_write_];
  const size_t index = next_write_++;
  ++writes_compared_;
  const bool saturated = (e.entry.flags & flag::kTableSaturated) != 0;
  const bool depth_range = (e.entry.flags & flag::kDepthRange) != 0;
  if (a.address == e.address && a.t_u == e.entry.t_u && a.t_v == e.entry.t_v &&
      a.s_u == e.entry.s_u && a.s_v == e.entry.s_v && a.saturated == saturated &&
      a.depth_range == depth_range)
    return true;
  const std::string where = fmt::format("table write #{} (fill)", index);
  if (a.address != e.address) return fail(where, "address", e.address, a.address);
  if (a.t_u != e.entry.t_u) return fail(where, "T.u", e.entry.t_u, a.t_u);
  if (a.t_v != e.entry.t_v) return fail(where, "T.v", e.entry.t_v, a.t_v);
  if (a.s_u != e.entry.s_u) return fail(where, "S.u", e.entry.s_u, a.s_u);
  if (a.s_v != e.entry.s_v) return fail(where, "S.v", e.entry.s_v, a.s_v);
  if (a.saturated != saturated) return fail(where, "table_saturated", saturated, a.saturated);
  if (a.depth_range != depth_range) return fail(where, "depth_range", depth_range, a.depth_range);
  return true;
}

bool Scoreboard::fragment(const RtlFragment& a) {
  if (next_ >= expected_.size())
    return fail(fmt::format("fragment #{} pixel ({}, {}) (the model emits only {})", next_, a.x,
                            a.y, expected_.size()),
                "count", static_cast<int64_t>(expected_.size()), static_cast<int64_t>(next_ + 1));
  const Fragment& e = expected_[next_];
  const size_t index = next_++;
  ++fragments_compared_;
  if (a.x == e.x && a.y == e.y && a.u == e.u && a.v == e.v && a.flags == e.flags) return true;
  const std::string where = fmt::format("fragment #{} pixel ({}, {})", index, e.x, e.y);
  if (a.x != e.x) return fail(where, "x", e.x, a.x);
  if (a.y != e.y) return fail(where, "y", e.y, a.y);
  if (a.u != e.u) return fail(where, "u", e.u, a.u);
  if (a.v != e.v) return fail(where, "v", e.v, a.v);
  return fail(where, "flags", e.flags, a.flags);
}

bool Scoreboard::record(const RtlRecord& a, int64_t stall_cycles) {
  const TriangleRecord& e = expected_record_;
  for (int bit = 0; bit < flag::kCount; ++bit)
    if (e.flags & (1u << bit)) ++flagged_[static_cast<size_t>(bit)];
  if (!e.x_major) ++y_major_;
  model_cycles_ += e.cycles;
  model_clocks_ += e.cycles + e.handshake_cycles;
  rtl_cycles_ += a.cycles;
  const std::string where = "record";
  if (!setup_seen_) return fail(where, "setup results observed", 1, 0);
  if (next_write_ != trace_.writes.size())
    return fail(where, "table writes", static_cast<int64_t>(trace_.writes.size()),
                static_cast<int64_t>(next_write_));
  if (next_ != expected_.size())
    return fail(where, "fragments", static_cast<int64_t>(expected_.size()),
                static_cast<int64_t>(next_));
  if (a.cycles != e.cycles + stall_cycles)
    return fail(fmt::format("record ({} stall cycles)", stall_cycles), "cycles",
                e.cycles + stall_cycles, a.cycles);
  if (a.lines != e.lines) return fail(where, "lines", e.lines, a.lines);
  if (a.bands != e.bands) return fail(where, "bands", e.bands, a.bands);
  if (a.pixels != e.pixels) return fail(where, "pixels", e.pixels, a.pixels);
  if (a.flags != e.flags) return fail(where, "flags", e.flags, a.flags);
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
