#include "size.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

#include "cli_checks.hpp"
#include "derived_widths.hpp"
#include "interrupt.hpp"
#include "regress.hpp"
#include "report.hpp"

namespace cdsim {

namespace {

const ParamInfo& info(const std::string& name) {
  for (const auto& p : param_table())
    if (name == p.name) return p;
  throw std::logic_error("unknown parameter " + name);
}

// Wide but valid starting widths (the walker's accumulator within 64 bits, the model's fast path)
// for the widths sizing changes; the others stay as the user set them, so
// that a design's result names only what its hardware depends on.
Widths widest(Widths w, const Design& design) {
  const std::vector<std::string>& sized = design.sized_widths;
  for (const auto& [name, value] : std::vector<std::pair<std::string, int>>{
           {"q_bits", 32}, {"plane_bits", 48}, {"g_frac", 30}, {"recip_bits", 32}, {"t_int", 20},
           {"t_frac", 24}, {"s_int", 20}, {"s_frac", 24}, {"d_frac", 24}, {"kim_frac", 16},
           {"persp_table_log2", 8}, {"eps_int", 16}, {"eps_frac", 30}, {"persp_frac", 30},
           {"adapt_depth", 14 - w.subpixel_bits}, {"adapt_uv_extra", 4}, {"adapt_bound_frac", 12}})
    if (std::find(sized.begin(), sized.end(), name) != sized.end()) set_param(w, name, std::min(value, info(name).max_value));
  if (design.kind == Design::Kind::ConstantDepth) w.table_depth = 65536 / 4;  // no banding while sizing
  return w;
}

// Whether a result has a flag (but banding, which the table depth decides) on
// more triangles than `allowed`.
bool saturates_more(const std::array<int64_t, flag::kCount>& allowed, const DesignResult& r) {
  for (int f = 0; f < flag::kCount; ++f)
    if ((1u << f) != flag::kBanded && r.flagged_triangles[f] > allowed[f]) return true;
  return false;
}

}  // namespace

double target_measure(const DesignResult& r, const ErrorTarget& target) {
  if (target.metric == "footprint") return r.error.footprint_max;
  if (target.statistic == "p99") return r.error.p99;
  if (target.statistic == "mean") return r.error.mean;
  return r.error.max;
}

Sizing size_design(const Design& design, const std::vector<const PreparedScene*>& scenes,
                   const Widths& user, const ErrorTarget& target,
                   const std::function<void(const std::string&, int)>& on_width, unsigned threads) {
  Sizing sizing;
  // A narrower width must not make the datapath saturate where the widest
  // widths do not: per scene, no flag (but banding, which the table depth
  // decides) on more triangles than at the widest. Otherwise a loose target,
  // above all a footprint one, would take widths that clamp the output of
  // triangles whose footprint is large (docs/choose.md).
  std::vector<std::array<int64_t, flag::kCount>>& allowed = sizing.widest_flags;
  // The worst scene's measure (infinite when a flag appears); results kept when asked.
  const auto worst = [&](const Widths& w, std::vector<DesignResult>* results) {
    double value = 0;
    for (size_t i = 0; i < scenes.size(); ++i) {
      ++sizing.evaluations;
      DesignResult r = evaluate(*scenes[i], design, w, true, nullptr, threads);
      value = std::max(value, target_measure(r, target));
      if (!allowed.empty() && saturates_more(allowed[i], r)) value = std::numeric_limits<double>::infinity();
      if (results) results->push_back(std::move(r));
      else if (value > target.max_error) break;  // one failing scene is enough
    }
    return value;
  };
  Widths w = widest(user, design);
  sizing.widths = w;
  std::vector<DesignResult> widest_results;
  sizing.error = worst(w, &widest_results);
  if (sizing.error > target.max_error) return sizing;
  sizing.reachable = true;
  for (const DesignResult& r : widest_results) allowed.push_back(r.flagged_triangles);
  // Error falls as a width grows, so a binary search suffices; the final run
  // below confirms the combination.
  for (const std::string& name : design.sized_widths) {
    const ParamInfo& p = info(name);
    int lo = p.min_value, hi = w.*(p.field);
    while (lo < hi) {
      throw_if_interrupted();
      const int mid = lo + (hi - lo) / 2;
      Widths trial = w;
      trial.*(p.field) = mid;
      bool fits = true;
      try {
        validate(trial);
      } catch (const std::invalid_argument&) {
        fits = false;
      }
      if (fits && worst(trial, nullptr) <= target.max_error) hi = mid;
      else lo = mid + 1;
    }
    w.*(p.field) = hi;
    if (on_width) on_width(name, hi);
  }
  // Table depth: the deepest band any scene fills, per unit of density.
  if (design.kind == Design::Kind::ConstantDepth) {
    std::vector<DesignResult> wide;
    worst(w, &wide);
    int64_t high_water = 0;
    for (const DesignResult& r : wide) high_water = std::max(high_water, r.table_high_water);
    w.table_depth = std::max<int>(info("table_depth").min_value,
                                  int((high_water + design.density - 1) / design.density));
    if (on_width) on_width("table_depth", w.table_depth);
  }
  sizing.widths = w;
  sizing.error = worst(w, &sizing.results);
  return sizing;
}

namespace {

// Runs the scenes at `trial`; takes it into `sizing` when every scene meets the
// target, none raises a flag on more triangles than at the widest widths, the
// cycles stay within max_slowdown times reference_cycles, and every scene runs
// at min_rate px/clk or more.
bool take_if_within(const Design& design, const std::vector<const PreparedScene*>& scenes,
                    const ErrorTarget& target, double max_slowdown, int64_t reference_cycles,
                    const Widths& trial, Sizing& sizing, double min_rate, unsigned threads) {
  std::vector<DesignResult> results;
  double error = 0;
  int64_t cycles = 0;
  bool flagged = false, slow = false;
  for (size_t i = 0; i < scenes.size(); ++i) {
    ++sizing.evaluations;
    results.push_back(evaluate(*scenes[i], design, trial, true, nullptr, threads));
    error = std::max(error, target_measure(results.back(), target));
    cycles += results.back().cycles;
    flagged = flagged || saturates_more(sizing.widest_flags[i], results.back());
    slow = slow || results.back().pixels_per_clock() < min_rate;
  }
  if (error > target.max_error || flagged || slow || double(cycles) > max_slowdown * double(reference_cycles))
    return false;
  sizing.widths = trial;
  sizing.results = std::move(results);
  sizing.error = error;
  return true;
}

}  // namespace

std::vector<int> setup_multiplier_choices() { return {1, 2, 4, 8}; }

void shrink_setup(const Design& design, const std::vector<const PreparedScene*>& scenes,
                  const ErrorTarget& target, double max_slowdown, int64_t reference_cycles, Sizing& sizing,
                  double min_rate, unsigned threads) {
  // A named setup engine stays: shared multipliers, or the products' register
  // (which only the one-multiplier-a-product engine has).
  if (!sizing.reachable || sizing.widths.setup_multipliers != 0 || sizing.widths.setup_product_register) return;
  for (const int m : setup_multiplier_choices()) {
    throw_if_interrupted();
    Widths trial = sizing.widths;
    trial.setup_multipliers = m;
    if (take_if_within(design, scenes, target, max_slowdown, reference_cycles, trial, sizing, min_rate, threads))
      return;
  }
}

void shrink_table(const Design& design, const std::vector<const PreparedScene*>& scenes,
                  const ErrorTarget& target, double max_slowdown, int64_t reference_cycles, Sizing& sizing,
                  double min_rate, unsigned threads) {
  if (!sizing.reachable || design.kind != Design::Kind::ConstantDepth) return;
  const int minimum = info("table_depth").min_value;
  for (int depth = sizing.widths.table_depth / 2; depth >= minimum; depth /= 2) {
    throw_if_interrupted();
    Widths trial = sizing.widths;
    trial.table_depth = depth;
    // A smaller table only bands more.
    if (!take_if_within(design, scenes, target, max_slowdown, reference_cycles, trial, sizing, min_rate, threads))
      break;
  }
}

CLI::App* add_size_command(CLI::App& app, SizeOptions& options) {
  CLI::App* size = app.add_subcommand(
      "size", "smallest widths and table depth that meet an error target on a scene");
  add_common(size, options.common);
  // 0 is refused: a fixed-point output equals the long-double reference only by
  // accident of the scene, so zero error is not a target widths can be sized for.
  size->add_option("--max-error", options.max_error, "error target, > 0 (texels, or footprint-normalised)")
      ->required()
      ->check(cli::number_in(0, std::numeric_limits<double>::infinity(), true));
  size->add_option("--metric", options.metric, "texels, or footprint (error / max(1, rho))")
      ->check(CLI::IsMember({"texels", "footprint"}))
      ->capture_default_str();
  size->add_option("--statistic", options.statistic, "which per-pixel statistic must meet it")
      ->check(CLI::IsMember({"max", "p99", "mean"}))
      ->capture_default_str();
  CLI::Option* verify = size->add_flag("--verify", options.verify,
                 "then run the RTL at the widths found against the model, bit and cycle exact: the "
                 "scene, then random triangles with back-pressure (constant-depth designs)");
  size->add_option("--verify-random", options.verify_random, "random triangles after the scene")
      ->check(cli::unsigned_in(0, 10'000'000))
      ->needs(verify)
      ->capture_default_str();
  size->add_option("--verify-backpressure", options.verify_backpressure,
                   "probability that the fragment sink stalls a cycle")
      ->check(cli::number_in(0.0, 0.95))
      ->needs(verify)
      ->capture_default_str();
  size->add_option("--rtl-cache", options.rtl_cache,
                   "folder of the RTL verilated for the widths found (as cdsim regress --rtl-cache)")
      ->needs(verify);
  return size;
}

int run_size_command(const SizeOptions& options) {
  const Widths user = widths_from(options.common);
  const std::vector<Design> designs =
      designs_from(options.common.designs.empty() ? "cd-linear" : options.common.designs);
  if (designs.size() != 1) throw std::invalid_argument("size sizes one design at a time (--design NAME)");
  const Design design = designs.front();
  if (options.metric == "footprint" && options.statistic != "max")
    throw std::invalid_argument("the footprint metric is kept as a maximum only: use --statistic max");
  if (options.verify && !has_rtl(design))
    throw std::invalid_argument(fmt::format(
        "--verify: design '{}' has no RTL yet; the RTL implements {}", design.name,
        rtl_design_names()));
  const PreparedScene scene = prepared_scene(options.common, user);
  std::cout << provenance(scene.scene, user);
  fmt::print("sizing {} for {} {} error <= {}\n\n", design.name, options.statistic, options.metric,
             options.max_error);
  std::fflush(stdout);

  const ErrorTarget target{options.max_error, options.metric, options.statistic};
  // One scene and one design: the error measurement takes every core.
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  const Sizing sizing = size_design(
      design, {&scene}, user, target,
      [](const std::string& name, int value) {
        fmt::print("  {:<12} {:>3}\n", name, value);
        std::fflush(stdout);
      },
      threads);
  if (!sizing.reachable) {
    fmt::print(stderr, "cdsim: not reachable: at the widest widths the {} {} error is {:.4g} > {}\n",
               options.statistic, options.metric, sizing.error, options.max_error);
    return 1;
  }
  const Widths w = sizing.widths;
  const double confirmed = sizing.error;
  fmt::print("\nresult ({} model runs): {}\n\n", sizing.evaluations, describe(w));
  std::cout << results_table(sizing.results, w);
  fmt::print("\n{}: {} {} error {:.4g} {} target {}\n", confirmed <= options.max_error ? "confirmed" : "NOT MET",
             options.statistic, options.metric, confirmed, confirmed <= options.max_error ? "<=" : ">",
             options.max_error);
  // The setup engine does not change the arithmetic, only the cycles: priced
  // here at the widths found (choose picks one within its --max-slowdown).
  fmt::print("\nsetup engine at these widths (setup_mul_bits {}): cycles and px/clk on the scene\n",
             w.setup_mul_bits);
  fmt::print("{:>20} {:>8} {:>12} {:>7} {:>9}\n", "setup_multipliers", "setup", "cycles", "px/clk", "slowdown");
  std::vector<int> setups = setup_multiplier_choices();
  setups.insert(setups.begin(), 0);
  int64_t parallel_cycles = 0;
  for (const int m : setups) {
    Widths trial = w;
    trial.setup_multipliers = m;
    if (m > 0) trial.setup_product_register = 0;  // shared multipliers register their sums anyway
    const DesignResult r = evaluate(scene, design, trial, false);  // cycles only
    if (m == 0) parallel_cycles = r.cycles;
    fmt::print("{:>20} {:>8} {:>12} {:>7.3f} {:>9.4f}{}\n", m == 0 ? "0 (one per product)" : std::to_string(m),
               derive(trial).setup_cycles, r.cycles, r.cycles ? double(r.pixels) / double(r.cycles) : 0.0,
               double(r.cycles) / double(parallel_cycles), m == w.setup_multipliers ? "  <- these widths" : "");
  }
  std::fflush(stdout);
  const int status = confirmed <= options.max_error ? 0 : 1;
  if (!options.verify) return status;
  fmt::print("\nverify: the RTL at these widths against the model\n");
  std::fflush(stdout);
  rtl::VerifyRequest request;
  request.widths = w;
  request.scenes = {options.common.scene};
  request.scene_options = options.common.scene_options;
  request.design = design.name;
  request.random = options.verify_random;
  request.backpressure = options.verify_backpressure;
  request.rtl_cache = options.rtl_cache;
  request.jobs = threads;  // in shards, one a core
  const int verified = rtl::verify_widths(request);
  return status != 0 ? status : verified;
}

}  // namespace cdsim
