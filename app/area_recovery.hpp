// cdsim area's recovering flow (`--flow recover`, docs/area.md, "Area
// recovery"): the unit is mapped twice, once at ABC's delay corner (the
// default flow's script) and once at its area corner (an area-recovering
// script), and each module of the netlist takes one of the two mappings. A
// module keeps the area mapping unless a path over the target period runs
// through one of its cells; the target is the clock the user gives, else the
// all-delay netlist's own critical path, so the unit's f_max is the delay
// flow's and the area is what the slack of the other modules buys back. This
// is what a designer's timing-driven synthesis does to the paths that have
// slack, with OpenSTA rather than ABC's load-blind delay model as the judge.
#pragma once

#include <filesystem>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sta.hpp"

namespace cdsim {

// A netlist as (module name, its structural Verilog), app/netlist_writer.hpp.
using ModuleTexts = std::vector<std::pair<std::string, std::string>>;

struct Recovery {
  std::set<std::string> area_modules;  // the modules that took the area mapping
  size_t modules = 0;                  // all the netlist's modules
  double target_ns = 0;                // the period every path was held to
  int rounds = 0;                      // timings of mixed netlists
  bool fell_back = false;              // no mix met it: every module delay-mapped
  StaReport delay;                     // the all-delay netlist's timing
  StaReport chosen;                    // the chosen netlist's timing
};

// Chooses each module's mapping, `delay` and `area` being the same netlist
// mapped two ways (the same modules, in any order). `target_ns` <= 0: the
// all-delay netlist's critical path. Round by round, the modules that hold
// the cells of the worst path over the target (by more than 0.5%) that runs through
// an area-mapped module go back to the delay mapping, until no path is over
// it; if a round moves no module (or after 16 rounds) while a path is still
// over it and over the all-delay netlist's critical path (a target no
// mapping meets), every module takes the delay mapping. Writes
// `work`/unit.v, the chosen netlist, and OpenSTA's scripts and logs under
// `work`. Throws std::runtime_error when the two netlists' modules differ.
Recovery recover_area(const ModuleTexts& delay, const ModuleTexts& area, double target_ns, const std::string& top,
                      const std::string& liberty, const std::string& clock, const std::filesystem::path& work,
                      const std::function<void(const std::string&)>& progress = {});

// The module that holds a cell, given its hierarchical name ("u_a/u_b/_12_"
// lies in the module of instance "u_a/u_b"; "_12_" in the top).
std::string module_of_cell(const StaReport& sta, const std::string& cell, const std::string& top);

}  // namespace cdsim
