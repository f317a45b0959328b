// cdsim choose: which design is cheapest for an accuracy target. For every
// design: size its widths on every scene given (cdsim size's search), pick
// the smallest scanline table whose banding keeps the cycles within a budget,
// synthesise the result (cdsim area), and rank the designs by total area,
// then cycles. The winner is then checked on the RTL (cdsim regress at its
// widths). docs/choose.md describes the search and its choices.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "design.hpp"
#include "scene.hpp"
#include "widths.hpp"

namespace cdsim {

struct ChooseOptions {
  std::vector<std::string> scenes;  // default: {"default"}
  SceneOptions scene_options;       // applied to every scene
  std::string designs;              // default: every design
  std::vector<std::string> settings;  // the unit's interface widths the user fixes
  double max_error = 0.5;
  std::string metric = "texels";
  std::string statistic = "max";
  double max_slowdown = 1.10;  // cycles of a banded table over those of an unbanded one
  double min_rate = 0.9;       // px/clk every scene must reach (0: no rate target; docs/choose.md)
  double clock_mhz = 0;        // the clock f_max must reach (0: no clock target)
  unsigned pipeline_steps = 3; // pipelining steps a design below the clock may take (0: none)
  std::string json_path;
  bool verify = true;          // regress the winner on the RTL
  size_t verify_random = 500;
  double verify_backpressure = 0.3;
  std::string rtl_cache, area_cache;
  std::string area_flow = "delay";  // --area-flow: AreaOptions::flow
  unsigned jobs = 0;           // designs sized, and syntheses, at a time (0: all cores)
};

CLI::App* add_choose_command(CLI::App& app, ChooseOptions& options);
// One more step of the pipelining of `block`, the block that sets a design's
// clock (its name in cdsim area's report), or none when that block has no
// knob, it is spent, or `settings` (--set NAME=VALUE) names it
// (docs/choose.md, "The pipelining it searches"): the correction adder's
// registers, the reciprocal's stages, the affine setup's divider bits a cycle,
// the setup engine's products' register, then its line register, or, when
// the path ends in one of its serial dividers (`path_end`, the critical
// path's end pin, names the instance), its divider bits a cycle (nothing when
// it ends in the multipliers' own registers), the fill's products' register for the
// paths into the scanline table.
std::optional<Widths> deeper_pipeline(const Design& design, const Widths& widths, const std::string& block,
                                      const std::vector<std::string>& settings, const std::string& path_end = "");
// What choose does with a pipelining step, from the f_max of the widths it
// keeps and of the step's: kept if it raised f_max; else, the first time,
// kept on trial (the next step is taken on top of it, for the block that then
// sets the clock), and the search ends the second.
enum class PipeliningVerdict { Keep, Trial, Stop };
PipeliningVerdict pipelining_verdict(double kept_fmax_mhz, double stepped_fmax_mhz, bool on_trial);
int run_choose_command(const ChooseOptions& options);

}  // namespace cdsim
