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
  expected_record_ = unit_for(job).run(job.triangle, &expected_);
}

bool Scoreboard::fail(const std::string& where, const char* field, int64_t expected,
                      int64_t actual) {
  ++mismatches_;
  mismatch_ = fmt::format(
      "MISMATCH seed {} triangle {} {}: field {}: expected {}, actual {}\n  triangle {}",
      seed_, index_, where, field, expected, actual, describe_job(*job_));
  return false;
}

bool Scoreboard::fragment(const RtlFragment& a) {
  if (next_ >= expected_.size())
    return fail(fmt::format("fragment #{} pixel ({}, {}) (the model emits only {})", next_, a.x,
                            a.y, expected_.size()),
                "count", static_cast<int64_t>(expected_.size()), static_cast<int64_t>(next_ + 1));
  const Fragment& e = expected_[next_];
  const std::string where = fmt::format("fragment #{} pixel ({}, {})", next_, e.x, e.y);
  ++next_;
  ++fragments_compared_;
  if (a.x != e.x) return fail(where, "x", e.x, a.x);
  if (a.y != e.y) return fail(where, "y", e.y, a.y);
  if (a.u != e.u) return fail(where, "u", e.u, a.u);
  if (a.v != e.v) return fail(where, "v", e.v, a.v);
  if (a.flags != e.flags) return fail(where, "flags", e.flags, a.flags);
  return true;
}

bool Scoreboard::record(const RtlRecord& a, int64_t stall_cycles) {
  const TriangleRecord& e = expected_record_;
  for (int bit = 0; bit < flag::kCount; ++bit)
    if (e.flags & (1u << bit)) ++flagged_[static_cast<size_t>(bit)];
  if (!e.x_major) ++y_major_;
  model_cycles_ += e.cycles;
  rtl_cycles_ += a.cycles;
  const std::string where = "record";
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

std::string Scoreboard::flag_census() const {
  std::string text = "flags (triangles):";
  for (int bit = 0; bit < flag::kCount; ++bit)
    text += fmt::format(" {}:{}", flag::name(bit), flagged_[static_cast<size_t>(bit)]);
  return text + fmt::format("; y-major triangles: {}", y_major_);
}

}  // namespace cdsim::rtl
