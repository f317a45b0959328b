#include "flagged_triangles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "exact.hpp"
#include "setup_engine.hpp"

namespace cdsim {
namespace {

std::string flag_names(uint32_t flags) {
  std::string names;
  for (int bit = 0; bit < flag::kCount; ++bit)
    if ((flags >> bit) & 1) names += (names.empty() ? "" : "|") + std::string(flag::name(bit));
  return names;
}

}  // namespace

void FlaggedTriangles::start(const Design& design) {
  design_ = design;
  tallies_.assign(scene_.unit.size(), Tally{});
}

void FlaggedTriangles::add(int64_t triangle, const Fragment& f, const ExactSample& exact) {
  Tally& t = tallies_[static_cast<size_t>(triangle)];
  const PixelError e = pixel_error(f, exact, widths_.out_frac);
  ++t.pixels;
  t.error_max = std::max(t.error_max, e.texels);
  t.footprint_max = std::max(t.footprint_max, e.footprint);
  if (f.flags & flag::kDatapath) {
    ++t.flagged;
    t.flags |= f.flags & flag::kDatapath;
  }
}

void FlaggedTriangles::finish() {
  const auto first = rows_.size();
  for (size_t i = 0; i < tallies_.size(); ++i) {
    if (tallies_[i].flagged == 0) continue;
    Row row{design_.name, static_cast<int64_t>(i), tallies_[i], false, {}};
    if (design_.kind == Design::Kind::ConstantDepth) {
      const Setup s = setup_engine(scene_.unit[i], design_, widths_, scene_.scene.width, scene_.scene.height);
      row.has_lines = true;
      row.geometry = line_geometry(scene_.scene.triangles[i], scene_.unit[i], s, widths_);
    }
    rows_.push_back(std::move(row));
  }
  // The worst first within the design.
  std::stable_sort(rows_.begin() + static_cast<std::ptrdiff_t>(first), rows_.end(),
                   [](const Row& a, const Row& b) { return a.tally.footprint_max > b.tally.footprint_max; });
  tallies_.clear();
}

void FlaggedTriangles::append(FlaggedTriangles&& other) {
  for (Row& row : other.rows_) rows_.push_back(std::move(row));
  other.rows_.clear();
}

std::string FlaggedTriangles::csv() const {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out),
                 "design,triangle,origin,flags,pixels,flagged_pixels,error_max,footprint_max,axis,depth_ratio,"
                 "horizon_gaps,lines,past_horizon,t_max,t_int_needed,t_int,s_max,s_int_needed,s_int\n");
  for (const Row& r : rows_) {
    fmt::format_to(std::back_inserter(out), "{},{},\"{}\",{},{},{},{},{}", r.design, r.triangle,
                   scene_.scene.triangles[static_cast<size_t>(r.triangle)].origin, flag_names(r.tally.flags),
                   r.tally.pixels, r.tally.flagged, r.tally.error_max, r.tally.footprint_max);
    if (r.has_lines) {
      const LineGeometry& g = r.geometry;
      fmt::format_to(std::back_inserter(out), ",{},{},{},{},{},{},{},{},{},{},{}\n", g.x_major ? "x" : "y",
                     g.depth_ratio, g.horizon_gaps, g.lines, g.past_horizon, g.t_max, g.t_int_needed,
                     widths_.t_int, g.s_max, g.s_int_needed, widths_.s_int);
    } else {
      fmt::format_to(std::back_inserter(out), ",,,,,,,,,,,\n");
    }
  }
  return fmt::to_string(out);
}

std::string FlaggedTriangles::table(size_t rows_per_design) const {
  fmt::memory_buffer out;
  const auto line = [&](auto&&... args) { fmt::format_to(std::back_inserter(out), args...); };
  line("\nflagged triangles (pixels with a datapath flag), the worst by footprint error first:\n");
  line("{:<17} {:>9} {:<38} {:>7} {:>7} {:>9} {:>9} {:>4} {:>10} {:>9} {:>7} {:>6} {:>12} {:>12}\n", "design",
       "triangle", "flags", "pixels", "flagged", "max_err", "fp_max", "axis", "depth_ratio", "horizon", "lines",
       "past", "T bits/have", "S bits/have");
  size_t shown = 0, of_design = 0;
  std::string design;
  for (const Row& r : rows_) {
    if (r.design != design) design = r.design, of_design = 0;
    if (of_design++ >= rows_per_design) continue;
    ++shown;
    line("{:<17} {:>9} {:<38} {:>7} {:>7} {:>9.3g} {:>9.3g}", r.design, r.triangle, flag_names(r.tally.flags),
         r.tally.pixels, r.tally.flagged, r.tally.error_max, r.tally.footprint_max);
    if (r.has_lines) {
      const LineGeometry& g = r.geometry;
      line(" {:>4} {:>10.4g} {:>9.3g} {:>7} {:>6} {:>12} {:>12}\n", g.x_major ? "x" : "y", g.depth_ratio,
           g.horizon_gaps, g.lines, g.past_horizon, fmt::format("{}/{}", g.t_int_needed, widths_.t_int),
           fmt::format("{}/{}", g.s_int_needed, widths_.s_int));
    } else {
      line("\n");
    }
  }
  if (rows_.empty()) line("(none)\n");
  if (shown < rows_.size()) line("... {} more rows in the CSV\n", rows_.size() - shown);
  line("horizon: the far vertex's distance to its plane's horizon, in line gaps; past: table lines beyond it "
       "(q <= 0); T, S bits: the signed integer bits their largest value on the held lines needs, and t_int, "
       "s_int\n");
  return fmt::to_string(out);
}

}  // namespace cdsim
