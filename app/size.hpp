// cdsim size: the smallest widths and table depth that meet an error target on
// a scene, found by coordinate descent from wide widths, then confirmed by
// running the model at the result; with --verify, regressed on the RTL at
// those widths (cdsim regress, verilated for them on first use).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

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

CLI::App* add_size_command(CLI::App& app, SizeOptions& options);
int run_size_command(const SizeOptions& options);

}  // namespace cdsim
