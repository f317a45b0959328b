// `cdsim regress`: the RTL (Verilated, under SystemC) against the C++ model.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "design.hpp"
#include "scene.hpp"
#include "scoreboard.hpp"
#include "widths.hpp"

namespace CLI {
class App;
}

namespace cdsim::rtl {

struct RegressOptions {
  std::string scene = "default";
  SceneOptions scene_options;
  size_t random = 0;                  // 0: the scene; else N random triangles instead
  uint64_t seed = 1;
  double backpressure = 0.0;
  std::string trace;
  std::string widths = "default";
  std::string design = "mix";
  int64_t only = -1;                  // -1: every triangle
  std::vector<std::string> settings;  // NAME=VALUE on top of `widths`
  std::string rtl_cache;              // folder of the RTL units verilated on first use
  bool scene_and_random = false;      // the scene, then `random` triangles (size --verify)
  std::vector<std::string> more_scenes;  // after `scene`, in the same stream (choose's check; --then-scene)
  size_t then_random = 0;             // --then-random N: scene_and_random with random = N
  std::string shard;                  // "I/N": every N-th triangle from the I-th (cdsim merge joins them)
  std::string json_path;              // the summary as JSON
  std::string coverage_dir;           // coverage data and report (regress --coverage)
  bool coverage_toggle = true;        // false: a coverage build without toggle points (--no-toggle)
  // The unit with every design of the scan unit's hardware, instead of one
  // with only the chosen designs' (--whole-unit).
  bool whole_unit = false;
};

// Registers the `regress` subcommand and its options on app
// (app/regress_cli.cpp: the command line needs no SystemC).
CLI::App* add_regress_command(CLI::App& app, RegressOptions& options);

// The widths of a built-in configuration (default, narrow, wide); throws
// std::invalid_argument naming the built ones.
Widths widths_of(const std::string& config);
// --design: one design, a comma-separated list taken in turn, or mix (every
// design with RTL); throws std::invalid_argument for a name without RTL.
std::vector<const Design*> designs_for(const std::string& name);
// The triangles of a run, numbered in the whole source: the scene, or
// `random` seeded random triangles, or both (scene_and_random; the scene then
// more_scenes, then the random ones), the designs
// taken in turn. Prints a "source:" line and describes the source in `source`.
std::vector<Job> source_jobs(const RegressOptions& options, const Widths& widths,
                             const std::vector<const Design*>& designs, std::string& source);

// `cdsim vectors`: the model's expectations of each block for a replay on a
// bench of the user's own, as $readmemh files (sim/vectors.cpp, docs/vectors.md).
struct VectorsOptions {
  RegressOptions source;  // scene or --random, --seed, --widths, --set, --design
  std::string out;        // folder the files go to
};
CLI::App* add_vectors_command(CLI::App& app, VectorsOptions& options);
int run_vectors_command(const VectorsOptions& options);

// `cdsim coverage DIR...` (sim/rtl_coverage.cpp).
struct CoverageOptions {
  std::vector<std::string> dirs;
  double min_lines = 0;  // percent
};
CLI::App* add_coverage_command(CLI::App& app, CoverageOptions& options);
int run_coverage_command(const CoverageOptions& options);
// Runs it with the parsed options; returns the process exit code. Throws
// Interrupted (interrupt.hpp) on SIGINT or SIGTERM.
int run_regress_command(const RegressOptions& options);

// Cycles the bench waits for a triangle's record before it reports a hang:
// 4 x (the model's cycles + the stalls expected from back-pressure p, pixels
// x p / (1 - p)) + 1000. The RTL's count is the model's plus the stalls, the
// stall count of a pixel is geometric with mean p / (1 - p), so a legal
// triangle exceeds this with negligible probability.
int64_t hang_cycle_limit(int64_t model_cycles, int64_t pixels, double backpressure);

// `cdsim size --verify`: regresses exactly these widths on the RTL, verilated
// into the cache on first use as for `cdsim regress --set`: the scene, then
// `random` seeded random triangles, with back-pressure. Prints what regress
// prints; returns its exit code (0: no mismatch).
struct VerifyRequest {
  Widths widths;
  // In one stream, each triangle with its scene's viewport (SystemC
  // elaborates a bench once per process, so one run must hold them all).
  std::vector<std::string> scenes = {"default"};
  SceneOptions scene_options;
  std::string design;  // a constant-depth design (the RTL has no other)
  size_t random = 2000;
  uint64_t seed = 1;
  double backpressure = 0.3;
  std::string rtl_cache;  // empty: the default cache folder
  // Shards run at once, each a `cdsim regress --shard I/N` of this process's
  // executable (SystemC elaborates one bench a process); 1: in this process.
  unsigned jobs = 1;
};
int verify_widths(const VerifyRequest& request);

}  // namespace cdsim::rtl
