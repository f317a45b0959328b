// cdsim size: the smallest widths and table depth that meet an error target on
// a scene, found by coordinate descent from wide widths, then confirmed by
// running the model at the result; with --verify, regressed on the RTL at
// those widths (cdsim regress, verilated for them on first use).
#pragma once

#include <CLI/CLI.hpp>
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "common.hpp"

namespace cdsim {

struct SizeOptions {
  CommonOptions common;
  double max_error = 0.5;
  std::string metric = "texels";    // texels | footprint
  std::string statistic = "max";    // max | p99 | mean
  bool verify = false;              // then regress the result on the RTL
  size_t verify_random = 2000;      // random triangles after the scene
  double verify_backpressure = 0.3;
  std::string rtl_cache;            // empty: the default cache folder
};

// What sizing must meet: `statistic` of `metric` <= max_error on every scene.
struct ErrorTarget {
  double max_error = 0.5;
  std::string metric = "texels";   // texels | footprint
  std::string statistic = "max";   // max | p99 | mean
};
double target_measure(const DesignResult& result, const ErrorTarget& target);

struct Sizing {
  bool reachable = false;     // false: not even the widest widths meet the target
  Widths widths;              // sized; table_depth the deepest band the scenes fill
  std::vector<DesignResult> results;  // per scene, at `widths`
  double error = 0;           // the worst scene's measure at `widths` (at the widest if unreachable)
  int evaluations = 0;        // model runs
  // Per scene, the triangles each flag marks at the widest widths: what a
  // narrower width or a smaller table may not exceed (banding aside).
  std::vector<std::array<int64_t, flag::kCount>> widest_flags;
};

// Coordinate descent from wide widths: each width the design's accuracy
// depends on, in turn, at the smallest value that still meets the target on
// every scene with the others where they stand; then the table depth of the
// deepest band. A width is taken only if no scene then raises a saturation
// flag on more triangles than at the widest widths. `on_width` (optional) is
// told each width as it is fixed.
Sizing size_design(const Design& design, const std::vector<const PreparedScene*>& scenes,
                   const Widths& user, const ErrorTarget& target,
                   const std::function<void(const std::string&, int)>& on_width = {}, unsigned threads = 1);

// The setup engine's multipliers tried, from the cheapest: M shared
// multipliers of setup_mul_bits (docs/area.md: each is smaller than M = 0,
// one multiplier per product, which is the sizing's start).
std::vector<int> setup_multiplier_choices();

// With the fully parallel setup engine (setup_multipliers 0, as sized), takes
// the first of setup_multiplier_choices() at which every scene still meets the
// target, raises no saturation flag on more triangles than at the widest
// widths, and the scenes' cycles stay within max_slowdown times
// reference_cycles (a shared engine sets a triangle up in more cycles), and
// every scene at min_rate px/clk or more. A setup_multipliers the sizing
// starts from other than 0 (the user's) stays.
void shrink_setup(const Design& design, const std::vector<const PreparedScene*>& scenes,
                  const ErrorTarget& target, double max_slowdown, int64_t reference_cycles, Sizing& sizing,
                  double min_rate = 0, unsigned threads = 1);

// Halves a reachable table design's table depth while every scene still meets
// the target and raises no saturation flag on more triangles than at the
// widest widths, and the scenes' cycles stay within max_slowdown times
// reference_cycles (a smaller table bands and refills more), every scene at
// min_rate px/clk or more. Updates the sizing's widths, results, error and
// evaluations.
void shrink_table(const Design& design, const std::vector<const PreparedScene*>& scenes,
                  const ErrorTarget& target, double max_slowdown, int64_t reference_cycles, Sizing& sizing,
                  double min_rate = 0, unsigned threads = 1);

CLI::App* add_size_command(CLI::App& app, SizeOptions& options);
int run_size_command(const SizeOptions& options);

}  // namespace cdsim
