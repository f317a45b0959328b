// The cdsim command line: every subcommand and option, with their checks
// (cli_checks.hpp), built apart from running them so that tests and the
// fuzzer (tests/fuzz/fuzz_cli.cpp) can parse an argv without executing a
// command. app/cdsim.cpp parses and runs.
#pragma once

#include <CLI/CLI.hpp>
#include <memory>
#include <string>

#include "area.hpp"
#include "area_model.hpp"
#include "choose.hpp"
#include "common.hpp"
#include "regress.hpp"
#include "render.hpp"
#include "size.hpp"
#include "sweep.hpp"

namespace cdsim {

struct Cli {
  CLI::App app{"cdsim: cycle-level simulator of the constant-depth scan texture unit"};
  // What the options parse into, per subcommand.
  CommonOptions run, bench, widths;
  std::string json_path;       // run --json
  std::string designs_json_path;  // designs --json
  bool show_worst = false;     // run --worst
  std::string dump_path;       // run --dump
  std::string flagged_path;    // run --flagged
  bool run_area = false;       // run --area
  std::string run_area_flow = "delay";  // run --area-flow
  int run_jobs = 0;            // run --jobs (0: all cores)
  double bench_seconds = 1.0;  // bench --seconds
  std::string sv_path;         // widths --sv
  rtl::RegressOptions regress;
  rtl::CoverageOptions coverage;
  rtl::VectorsOptions vectors;
  SweepOptions sweep;
  MergeOptions merge;
  RenderOptions render;
  SizeOptions size;
  AreaOptions area;
  AreaModelOptions area_model;
  ChooseOptions choose;
  // The subcommands; none given means run.
  CLI::App *run_command = nullptr, *bench_command = nullptr, *widths_command = nullptr,
           *regress_command = nullptr, *sweep_command = nullptr, *designs_command = nullptr,
           *hard_cases_command = nullptr, *render_command = nullptr, *size_command = nullptr,
           *area_command = nullptr, *choose_command = nullptr, *area_model_command = nullptr,
           *merge_command = nullptr, *coverage_command = nullptr,
           *vectors_command = nullptr;
};

// Builds the whole command line. The options refer into the Cli, which
// therefore stays where it is built.
std::unique_ptr<Cli> make_cli();

}  // namespace cdsim
