// The options of `cdsim regress` (sim/regress.cpp runs it): apart from the
// bench so that the command line builds, and is fuzzed, without SystemC.
#include <CLI/CLI.hpp>

#include <limits>

#include "cli_checks.hpp"
#include "loaders/scene_cli.hpp"
#include "regress.hpp"

namespace cdsim::rtl {

// More random triangles than this are refused: each job is held in memory.
constexpr uint64_t kMaxRandomTriangles = 10'000'000;

namespace {

// The options that say which triangles at which widths and designs: regress
// and vectors take the same.
void add_source_options(CLI::App* cmd, RegressOptions& options) {
  add_scene_options(cmd, options.scene, options.scene_options);
  CLI::Option* random =
      cmd->add_option("--random", options.random,
                      "N seeded random triangles (with SPEC §9 hard cases) instead of a scene")
          ->check(cli::unsigned_in(1, kMaxRandomTriangles));
  for (const char* scene_option : {"--scene", "--camera", "--spawn", "--resolution"})
    random->excludes(cmd->get_option(scene_option));
  cmd->add_option("--seed", options.seed, "seed of the random triangles and of the back-pressure")
      ->check(cli::unsigned_in(0, std::numeric_limits<uint64_t>::max()))
      ->capture_default_str();
  cmd->add_option("--widths", options.widths,
                  "width configuration: default, narrow or wide (the base that --set changes)")
      ->capture_default_str();
  cmd->add_option("--set", options.settings,
                  "NAME=VALUE: change a width or microarchitecture parameter (see 'cdsim widths'); "
                  "repeatable, each parameter once");
  cmd->add_option("--design", options.design,
                  "a design (see 'cdsim designs'), a comma-separated list, or mix (the seventeen designs of the scan unit, in turn; adaptive has a unit of its own: regress it alone)")
      ->capture_default_str();
}

}  // namespace

CLI::App* add_regress_command(CLI::App& app, RegressOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "regress", "run the SystemVerilog RTL (Verilator + SystemC) against the model, bit and cycle exact");
  add_source_options(cmd, options);
  cmd->get_option("--set")->description(
      "NAME=VALUE: change a width or microarchitecture parameter (see 'cdsim widths'); "
      "repeatable, each parameter once. Each unit at each widths is verilated on first "
      "use and cached (--rtl-cache)");
  cmd->add_option("--backpressure", options.backpressure,
                  "probability that the fragment sink stalls a cycle")
      ->check(cli::number_in(0.0, 0.95))
      ->capture_default_str();
  cmd->add_option("--trace", options.trace, "write an FST waveform of the whole run to this file");
  cmd->add_option("--rtl-cache", options.rtl_cache,
                  "folder of the RTL units verilated on first use (default $XDG_CACHE_HOME/cdsim/rtl "
                  "or ~/.cache/cdsim/rtl)");
  cmd->add_option("--shard", options.shard,
                  "I/N: run only the I-th of N shards (every N-th triangle from the I-th, each with "
                  "the back-pressure it has in the whole run); cdsim merge joins the summaries");
  cmd->add_option("--json", options.json_path, "also write the summary as JSON (what cdsim merge joins)");
  CLI::Option* coverage = cmd->add_option(
      "--coverage", options.coverage_dir,
      "run a coverage build of the RTL (line, branch, toggle and the cover points of "
      "sim/cover/cd_scan_cover.sv) and add this run's data to DIR, which then holds "
      "the merged coverage.info, coverage.json and an HTML report (docs/coverage.md)");
  cmd->add_flag("--no-toggle{false}", options.coverage_toggle,
                "with --coverage: leave out the toggle points (line, branch and cover points "
                "only), for a coverage build that builds and runs several times faster")
      ->needs(coverage);
  cmd->add_flag("--whole-unit", options.whole_unit,
                "run the unit with every design's hardware, rather than one that holds only the "
                "chosen designs' datapaths (as cdsim area synthesises it; it simulates faster)");
  cmd->add_option("--only", options.only, "run only triangle N of the source, from 0 (to chase a mismatch)")
      ->check(cli::integer_in(0, std::numeric_limits<int64_t>::max()));
  // The stream of size's and choose's RTL check, which runs it in shards.
  CLI::Option* then_scene =
      cmd->add_option("--then-scene", options.more_scenes,
                      "another scene after --scene, in the same stream at its own viewport (repeatable; "
                      "--camera, --spawn and --resolution apply to every scene)");
  CLI::Option* then_random =
      cmd->add_option("--then-random", options.then_random,
                      "after the scene(s), N seeded random triangles in the same stream (as size --verify)")
          ->check(cli::unsigned_in(1, kMaxRandomTriangles));
  cmd->get_option("--random")->excludes(then_scene)->excludes(then_random);
  return cmd;
}

CLI::App* add_vectors_command(CLI::App& app, VectorsOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "vectors",
      "write the model's expectations of each block (setup engine, table fill, fragments, "
      "records) for the triangles as $readmemh files with a manifest, for a bench of your own "
      "(tests/vectors/cd_scan_vectors_tb.sv replays them; docs/vectors.md)");
  add_source_options(cmd, options.source);
  cmd->get_option("--seed")->description("seed of the random triangles");
  cmd->add_option("--out", options.out, "folder to write the vectors into (created; its files replaced)")
      ->required();
  return cmd;
}

CLI::App* add_coverage_command(CLI::App& app, CoverageOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "coverage",
      "merge the coverage data that regress --coverage wrote into DIR (and more folders) and "
      "report it: lcov .info, HTML, JSON and the figures; --min-lines fails below a line coverage");
  cmd->add_option("dirs", options.dirs, "folders of coverage data (*.dat); the report goes to the first")
      ->required();
  cmd->add_option("--min-lines", options.min_lines,
                  "exit 1 if the line coverage of rtl/ is below this percentage")
      ->check(CLI::Range(0.0, 100.0));
  return cmd;
}

}  // namespace cdsim::rtl
