// `cdsim regress`: the triangles (a scene or seeded random ones), the widths
// (a built-in configuration, or any widths with --set, verilated on first use
// into a cache by rtl_cache.cpp), and the one bench of bench.hpp that runs the
// Verilated scan unit against the C++ model.
#include "regress.hpp"

#include "loaders/scene_cli.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <systemc.h>

#include <cstdlib>
#include <iostream>

#include "Vcd_scan_unit_default.h"
#include "Vcd_scan_unit_narrow.h"
#include "Vcd_scan_unit_wide.h"
#include "bench.hpp"
#include "evaluate.hpp"
#include "random_triangles.hpp"
#include "rtl_cache.hpp"
#include "scene.hpp"
#include "scoreboard.hpp"

// SystemC's library refers to sc_main; cdsim has its own main and starts the
// kernel itself, so this one is never called.
int sc_main(int, char**) { return 1; }

namespace cdsim::rtl {

namespace {

struct Options {
  std::string scene = "default";
  SceneOptions scene_options;
  size_t random = 0;
  uint64_t seed = 1;
  double backpressure = 0.0;
  std::string trace;
  std::string widths = "default";
  std::string design = "mix";
  int64_t only = -1;
  std::vector<std::string> settings;  // NAME=VALUE on top of `widths`
  std::string rtl_cache;              // folder of the RTL verilated for --set widths
  bool scene_and_random = false;      // the scene, then `random` triangles (size --verify)
};
Options options;

struct WidthConfig {
  const char* name;
  const char* settings;  // overrides of model/widths.def, "name=value ..."
};
const WidthConfig kConfigs[] = {
#define X(name, settings) {#name, settings},
#include "rtl_configs.def"
#undef X
};

Widths widths_of(const std::string& config) {
  for (const auto& c : kConfigs) {
    if (config != c.name) continue;
    Widths widths;
    std::string settings = c.settings;
    size_t start = 0;
    while (start < settings.size()) {
      size_t end = settings.find(' ', start);
      if (end == std::string::npos) end = settings.size();
      if (end > start) apply_setting(widths, settings.substr(start, end - start));
      start = end + 1;
    }
    validate(widths);
    return widths;
  }
  std::string known;
  for (const auto& c : kConfigs) known += fmt::format(" {}", c.name);
  throw std::invalid_argument(
      fmt::format("unknown width configuration '{}'; built:{}", config, known));
}

std::vector<const Design*> designs_for(const std::string& name) {
  std::vector<const Design*> out;
  if (name == "mix") {
    for (const Design& d : all_designs())
      if (d.kind == Design::Kind::ConstantDepth) out.push_back(&d);
    return out;
  }
  const Design& d = find_design(name);
  if (d.kind != Design::Kind::ConstantDepth)
    throw std::invalid_argument(fmt::format(
        "design '{}' has no RTL; the RTL implements cd-none, cd-linear, cd-dense2, cd-dense4, "
        "cd-dense2-linear (or 'mix': each in turn)", name));
  out.push_back(&d);
  return out;
}

}  // namespace

CLI::App* add_regress_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "regress", "run the SystemVerilog RTL (Verilator + SystemC) against the model, bit and cycle exact");
  add_scene_options(cmd, options.scene, options.scene_options);  // ignored with --random
  cmd->add_option("--random", options.random, "N seeded random triangles (with SPEC §9 hard cases)");
  cmd->add_option("--seed", options.seed, "seed of the random triangles and of the back-pressure")
      ->capture_default_str();
  cmd->add_option("--backpressure", options.backpressure,
                  "probability that the fragment sink stalls a cycle")
      ->check(CLI::Range(0.0, 0.95))
      ->capture_default_str();
  cmd->add_option("--trace", options.trace, "write an FST waveform of the whole run to this file");
  cmd->add_option("--widths", options.widths,
                  "width configuration: default, narrow or wide (the base that --set changes)")
      ->capture_default_str();
  cmd->add_option("--set", options.settings,
                  "NAME=VALUE: change a width or microarchitecture parameter (see 'cdsim widths'); "
                  "repeatable. Widths no configuration has are verilated on first use and cached");
  cmd->add_option("--rtl-cache", options.rtl_cache,
                  "folder of the RTL verilated for --set widths (default $XDG_CACHE_HOME/cdsim/rtl "
                  "or ~/.cache/cdsim/rtl)");
  cmd->add_option("--design", options.design,
                  "cd-none, cd-linear, cd-dense2, cd-dense4, cd-dense2-linear, or mix (each in turn)")
      ->capture_default_str();
  cmd->add_option("--only", options.only, "run only triangle N of the source (to chase a mismatch)");
  return cmd;
}

namespace {

// The built-in configuration with exactly these widths, or "" if none.
std::string builtin_config_of(const Widths& widths) {
  for (const auto& c : kConfigs)
    if (describe(widths_of(c.name)) == describe(widths)) return c.name;
  return "";
}

// Runs the bench at the widths of `options`: a built-in configuration, one with
// --set on top, or exactly `given` (size --verify). Widths that no built-in
// configuration has run on the RTL verilated for them into the cache.
int regress(const Widths* given) {
  Widths widths = given ? *given : widths_of(options.widths);
  for (const std::string& s : options.settings) apply_setting(widths, s);
  validate(widths);
  const bool exact = given || !options.settings.empty();
  const std::string builtin = exact ? builtin_config_of(widths) : options.widths;
  std::string label = given ? "as sized" : options.widths;
  if (!options.settings.empty()) label += " with";
  for (const std::string& s : options.settings) label += " " + s;
  if (exact && !builtin.empty()) label += fmt::format(" (= built-in '{}')", builtin);
  const std::vector<const Design*> designs = designs_for(options.design);
  std::cout << fmt::format("regress: seed {}\n", options.seed);
  std::vector<Job> jobs;
  if (options.random > 0 && !options.scene_and_random) {
    jobs = random_jobs(options.random, options.seed, widths, designs);
    std::cout << fmt::format("source: {} random triangles (seed {})\n", options.random, options.seed);
  } else {
    const PreparedScene scene = prepare(load_scene(options.scene, options.scene_options), widths);
    for (size_t i = 0; i < scene.unit.size(); ++i) {
      Job job;
      job.triangle = scene.unit[i];
      job.design = designs[i % designs.size()];
      job.viewport_width = scene.scene.width;
      job.viewport_height = scene.scene.height;
      job.origin = fmt::format("scene {} triangle {}", scene.scene.name, i);
      jobs.push_back(std::move(job));
    }
    std::cout << fmt::format("source: scene {} ({} triangles, {}x{})\n", scene.scene.name,
                             jobs.size(), scene.scene.width, scene.scene.height);
  }
  if (options.random > 0 && options.scene_and_random) {
    for (Job& job : random_jobs(options.random, options.seed, widths, designs))
      jobs.push_back(std::move(job));
    std::cout << fmt::format("source: then {} random triangles (seed {})\n", options.random,
                             options.seed);
  }
  if (options.only >= 0) {
    if (static_cast<size_t>(options.only) >= jobs.size())
      throw std::invalid_argument(fmt::format("--only {}: the source has {} triangles", options.only, jobs.size()));
    jobs = {jobs[static_cast<size_t>(options.only)]};
    std::cout << fmt::format("only triangle {}: {}\n", options.only, describe_job(jobs[0]));
  }
  std::cout << fmt::format("widths: {} ({})\n", label, describe(widths));
  std::cout << fmt::format("design: {}, back-pressure {}\n", options.design, options.backpressure);
  std::cout.flush();
  const BenchOptions bench_options{options.seed, options.backpressure, options.trace};
  if (builtin.empty()) {
    const RunBench run_custom = load_custom_rtl(widths, options.rtl_cache);
    return run_custom(&jobs, &widths, &bench_options);
  }
  if (builtin == "default") return run_bench<Vcd_scan_unit_default>(jobs, widths, bench_options);
  if (builtin == "narrow") return run_bench<Vcd_scan_unit_narrow>(jobs, widths, bench_options);
  return run_bench<Vcd_scan_unit_wide>(jobs, widths, bench_options);
}

}  // namespace

int run_regress_command() {
  try {
    return regress(nullptr);
  } catch (const std::exception& e) {
    std::cerr << "cdsim regress: error: " << e.what() << '\n';
    return 2;
  }
}

int verify_widths(const VerifyRequest& request) {
  options = Options{};
  options.scene = request.scene;
  options.scene_options = request.scene_options;
  options.scene_and_random = true;
  options.random = request.random;
  options.seed = request.seed;
  options.backpressure = request.backpressure;
  options.design = request.design;
  options.rtl_cache = request.rtl_cache;
  try {
    return regress(&request.widths);
  } catch (const std::exception& e) {
    std::cerr << "cdsim size --verify: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace cdsim::rtl
