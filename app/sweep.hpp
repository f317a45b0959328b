// cdsim sweep: every combination of swept parameters, for every design, on
// all cores, written as one CSV and one JSON row per (scene, design, widths).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "common.hpp"
#include "sweep_file.hpp"

namespace cdsim {

// Larger sweeps are refused unless --yes is given; above the hard limit they
// are refused regardless (every configuration and its result are held in memory).
constexpr uint64_t kSweepConfirmLimit = 100'000;
constexpr uint64_t kSweepHardLimit = 10'000'000;

struct SweepOptions {
  CommonOptions common;  // its --set entries may be ranges: NAME=LO:HI[:STEP] or NAME=A,B,C
  std::string file;      // sweep file (sweep_file.hpp)
  std::string out = "sweep-out";
  int jobs = 0;          // worker threads; 0 (not given): all cores
  bool yes = false;      // run more than kSweepConfirmLimit configurations
  bool area = false;     // also synthesise each distinct configuration (cdsim area, cached)
  bool area_model = false;  // area by the component area model instead (area_model.hpp)
  std::string area_flow = "delay";  // --area-flow: AreaOptions::flow
  std::string shard;     // "I/N": only the configurations of that shard (cdsim merge joins them)
};

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options);
int run_sweep_command(const SweepOptions& options);

// cdsim merge: the shards of one sweep joined into the files the whole sweep writes.
struct MergeOptions {
  std::string out;
  std::vector<std::string> shards;
};
CLI::App* add_merge_command(CLI::App& app, MergeOptions& options);
int run_merge_command(const MergeOptions& options);

}  // namespace cdsim
