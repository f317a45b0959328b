#include "report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "build_info.hpp"

namespace cdsim {

std::string build_id() {
  return fmt::format("cdsim {} ({}, {})", kBuildRevision, kBuildCompiler, kBuildType);
}

std::string provenance(const Scene& scene, const Widths& widths) {
  return fmt::format("scene: {} ({} triangles; {})\nwidths: {}\nseed: none (deterministic)\nbuild: {}\n",
                     scene.name, scene.triangles.size(), scene.description, describe(widths),
                     build_id());
}

namespace {

std::string flag_summary(const DesignResult& r) {
  std::string out;
  for (int bit = 0; bit < flag::kCount; ++bit) {
    const int64_t count = r.flagged_triangles[size_t(bit)];
    if (count == 0) continue;
    if (!out.empty()) out += ' ';
    out += fmt::format("{}:{}", flag::name(bit), count);
  }
  return out.empty() ? "-" : out;
}

}  // namespace

std::string results_table(const std::vector<DesignResult>& results, const Widths& widths) {
  std::string out = fmt::format(
      "{:<17} {:>9} {:>10} {:>6} {:>6} {:>10} {:>9} {:>9} {:>9} {:>9} {:>8} {:>10}  {}\n", "design",
      "pixels", "cycles", "px/clk", "depth", "table_bits", "mean_err", "p99_err", "max_err",
      "fp_max", "texel%", "flagged_px", "flags (triangles)");
  for (const DesignResult& r : results) {
    out += fmt::format("{:<17} {:>9} {:>10} {:>6.3f} {:>6} {:>10} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>8.4f} {:>10}  {}\n",
                       r.design.name, r.pixels, r.cycles, r.pixels_per_clock(), r.table_depth,
                       r.table_bits, r.error.mean, r.error.p99, r.error.max,
                       r.error.footprint_max, 100.0 * r.error.texel_mismatch, r.flagged_pixels, flag_summary(r));
  }
  out += fmt::format("errors in texels against the exact reference (max(|du|,|dv|) per pixel); "
                     "texel% = pixels whose nearest texel differs; output LSB = 2^-{}; flagged_px = pixels "
                     "with a datapath flag (table_saturated, output_saturated, depth_range, neighbour_dropped)\n",
                     widths.out_frac);
  // The same statistics without the flagged pixels, so that a few wild
  // pixels cannot hide in the statistics of all of them.
  const bool any_flagged =
      std::any_of(results.begin(), results.end(), [](const DesignResult& r) { return r.flagged_pixels > 0; });
  if (any_flagged) {
    out += fmt::format("\nerrors over the pixels without a datapath flag:\n"
                       "{:<17} {:>9} {:>9} {:>9} {:>9} {:>9} {:>8}\n",
                       "design", "pixels", "mean_err", "p99_err", "max_err", "fp_max", "texel%");
    for (const DesignResult& r : results)
      out += fmt::format("{:<17} {:>9} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>8.4f}\n", r.design.name,
                         r.pixels - r.flagged_pixels, r.error_unflagged.mean, r.error_unflagged.p99,
                         r.error_unflagged.max, r.error_unflagged.footprint_max,
                         100.0 * r.error_unflagged.texel_mismatch);
  }
  for (const DesignResult& r : results)
    if (r.design.fallback)
      out += fmt::format("{}: the divide fallback walked {} of {} triangles, {} pixels ({:.2f}%; far vertex within "
                         "2^{} line gaps of the horizon)\n",
                         r.design.name, r.fallback_triangles, r.triangles, r.fallback_pixels,
                         r.pixels ? 100.0 * double(r.fallback_pixels) / double(r.pixels) : 0.0,
                         widths.fallback_gaps_log2);
  std::string model_only;
  for (const DesignResult& r : results)
    if (!has_rtl(r.design)) model_only += (model_only.empty() ? "" : ", ") + r.design.name;
  if (!model_only.empty())
    out += fmt::format("model only, no RTL yet: {} (its cycles are the model's, not checked against RTL)\n",
                       model_only);
  return out;
}

std::string cycle_breakdown_table(const std::vector<DesignResult>& results) {
  // Each triangle's clocks, from the cycle after the previous record to its own
  // record, by what bound them (model/timing.hpp): the back end waiting for
  // the front end's setup (accept included), table fill, walk, and the record.
  std::string out = fmt::format(
      "\ncycles by phase (each triangle's clocks, from the cycle after the previous record to its own "
      "record, by what bound them):\n"
      "{:<17} {:>11} {:>7} {:>10} {:>7} {:>10} {:>7} {:>10} {:>7} {:>8} {:>6}\n",
      "design", "setup-bound", "share", "fill-bound", "share", "walk", "share", "record", "share", "px/tri",
      "px/clk");
  const auto share = [](int64_t part, int64_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; };
  for (const DesignResult& r : results)
    out += fmt::format("{:<17} {:>11} {:>6.1f}% {:>10} {:>6.1f}% {:>10} {:>6.1f}% {:>10} {:>6.1f}% {:>8.2f} {:>6.3f}\n",
                       r.design.name, r.setup_cycles, share(r.setup_cycles, r.cycles), r.fill_cycles,
                       share(r.fill_cycles, r.cycles), r.walk_cycles, share(r.walk_cycles, r.cycles),
                       r.record_cycles, share(r.record_cycles, r.cycles),
                       r.triangles ? double(r.pixels) / double(r.triangles) : 0.0, r.pixels_per_clock());
  return out;
}

std::string worst_pixels(const std::vector<DesignResult>& results, const Scene& scene,
                         const Widths& widths) {
  std::string out = "worst pixel per design:\n";
  const double lsb = std::ldexp(1.0, -widths.out_frac);
  for (const DesignResult& r : results) {
    if (r.worst.triangle < 0) continue;
    const Fragment& f = r.worst.fragment;
    out += fmt::format("  {:<17} triangle {} ({}) pixel ({}, {}): u,v = ({:.4f}, {:.4f}) exact ({:.4f}, {:.4f}) flags {:#x}\n",
                       r.design.name, r.worst.triangle,
                       scene.triangles[size_t(r.worst.triangle)].origin, f.x, f.y, double(f.u) * lsb,
                       double(f.v) * lsb, r.worst.exact_u, r.worst.exact_v, f.flags);
  }
  return out;
}

nlohmann::json results_json(const Scene& scene, const Widths& widths,
                            const std::vector<DesignResult>& results) {
  nlohmann::json j;
  j["scene"] = {{"name", scene.name},
                {"description", scene.description},
                {"triangles", scene.triangles.size()},
                {"resolution", {scene.width, scene.height}}};
  for (const auto& p : param_table()) j["widths"][p.name] = widths.*(p.field);
  j["build"] = build_id();
  j["seed"] = nullptr;
  j["designs"] = nlohmann::json::array();
  for (const DesignResult& r : results) {
    nlohmann::json d;
    d["name"] = r.design.name;
    d["has_rtl"] = has_rtl(r.design);  // false: the cycles are the model's alone
    d["pixels"] = r.pixels;
    d["cycles"] = r.cycles;
    d["pixels_per_clock"] = r.pixels_per_clock();
    d["cycle_breakdown"] = {{"setup_bound", r.setup_cycles}, {"fill_bound", r.fill_cycles},
                             {"walk", r.walk_cycles}, {"record", r.record_cycles}};
    d["table_depth"] = r.table_depth;
    d["table_word_bits"] = r.table_word_bits;
    d["table_bits"] = r.table_bits;
    d["table_high_water"] = r.table_high_water;
    d["lines_filled"] = r.lines;
    d["triangles"] = r.triangles;
    d["banded_triangles"] = r.banded_triangles;
    if (r.design.fallback) {
      d["fallback_triangles"] = r.fallback_triangles;
      d["fallback_pixels"] = r.fallback_pixels;
    }
    d["x_major_triangles"] = r.x_major_triangles;
    d["y_major_triangles"] = r.y_major_triangles;
    const auto stats = [](const ErrorStats& e) {
      return nlohmann::json{{"mean", e.mean},
                            {"rms", e.rms},
                            {"p99", e.p99},
                            {"max", e.max},
                            {"footprint_max", e.footprint_max},
                            {"texel_mismatch", e.texel_mismatch},
                            {"over_lsb", e.over_lsb}};
    };
    d["error"] = stats(r.error);  // every pixel
    d["flagged_pixels"] = r.flagged_pixels;
    d["error_unflagged"] = stats(r.error_unflagged);
    for (int bit = 0; bit < flag::kCount; ++bit)
      d["flags"][flag::name(bit)] = r.flagged_triangles[size_t(bit)];
    j["designs"].push_back(d);
  }
  return j;
}

}  // namespace cdsim
