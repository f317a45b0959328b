// cdsim sweep: every combination of swept parameters, for every design, on
// all cores, written as one CSV and one JSON row per (scene, design, widths).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "common.hpp"

namespace cdsim {

struct SweepOptions {
  CommonOptions common;  // its --set entries may be ranges: NAME=LO:HI[:STEP] or NAME=A,B,C
  std::string file;      // sweep file: the same NAME=... lines, '#' comments, "design LIST"
  std::string out = "sweep-out";
  int jobs = 0;          // 0: all cores
};

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options);
int run_sweep_command(const SweepOptions& options);

// One sweep axis: a parameter and the values it takes.
struct SweepAxis {
  std::string name;
  std::vector<int> values;
};
// Parses "NAME=LO:HI[:STEP]", "NAME=A,B,C" or "NAME=V"; checks every value's range.
SweepAxis parse_axis(const std::string& text);

}  // namespace cdsim
