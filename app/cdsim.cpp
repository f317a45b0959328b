// cdsim: command-line front of the constant-depth scan unit simulator.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include "area.hpp"
#include "common.hpp"
#include "render.hpp"
#include "size.hpp"
#include "sweep.hpp"
#include "evaluate.hpp"
#include "hard_cases.hpp"
#include "regress.hpp"
#include "report.hpp"
#include "loaders/scene_cli.hpp"
#include "scene.hpp"
#include "derived_widths.hpp"
#include "widths.hpp"

namespace {

using namespace cdsim;

int run_command(const CommonOptions& options, const std::string& json_path, bool show_worst) {
  const Widths widths = widths_from(options);
  const std::vector<Design> designs = parse_design_list(options.designs);
  const PreparedScene scene = prepare(load_scene(options.scene, options.scene_options), widths);
  std::cout << provenance(scene.scene, widths) << '\n';
  std::vector<DesignResult> results;
  for (const Design& d : designs) {
    if (isatty(fileno(stderr))) fmt::print(stderr, "running {} ...\r", d.name);
    results.push_back(evaluate(scene, d, widths));
  }
  std::cout << results_table(results, widths);
  if (show_worst) std::cout << worst_pixels(results, scene.scene, widths);
  if (!json_path.empty()) {
    std::ofstream out(json_path);
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write", json_path));
    out << results_json(scene.scene, widths, results).dump(2) << '\n';
    std::cout << "wrote " << json_path << '\n';
  }
  return 0;
}

int bench_command(const CommonOptions& options, double seconds) {
  const Widths widths = widths_from(options);
  const std::vector<Design> designs = parse_design_list(options.designs);
  const PreparedScene scene = prepare(load_scene(options.scene, options.scene_options), widths);
  std::cout << provenance(scene.scene, widths);
  fmt::print("single-threaded model throughput, error measurement off, at least {} s per design\n\n",
             seconds);
  for (const Design& d : designs) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    int64_t pixels = 0, passes = 0;
    double elapsed = 0;
    do {
      pixels += evaluate(scene, d, widths, false).pixels;
      ++passes;
      elapsed = std::chrono::duration<double>(clock::now() - start).count();
    } while (elapsed < seconds);
    fmt::print("{:<17} {:>4} passes {:>11} pixels in {:6.2f} s  {:8.1f} M pixels/s\n", d.name,
               passes, pixels, elapsed, double(pixels) / elapsed / 1e6);
  }
  return 0;
}

int widths_command(const CommonOptions& options, const std::string& sv_path) {
  const Widths widths = widths_from(options);
  if (!sv_path.empty()) {
    const std::string text = rtl_header(widths, "custom");
    if (sv_path == "-") {
      std::cout << text;
      return 0;
    }
    std::ofstream out(sv_path);
    out << text;
    out.close();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write", sv_path));
    std::cout << "wrote " << sv_path << '\n';
    return 0;
  }
  fmt::print("{:<18} {:>7} {:>7} {:>7}  {}\n", "parameter", "value", "min", "max", "meaning");
  for (const auto& p : param_table())
    fmt::print("{:<18} {:>7} {:>7} {:>7}  {}\n", p.name, widths.*(p.field), p.min_value,
               p.max_value, p.meaning);
  const DerivedWidths derived = derive(widths);
  fmt::print("\n{:<24} {:>7}  {}\n", "derived (RTL)", "value", "meaning");
  for (const auto& p : derived_table())
    fmt::print("{:<24} {:>7}  {}\n", p.name, derived.*(p.field), p.meaning);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cdsim: cycle-level simulator of the constant-depth scan texture unit"};
  app.require_subcommand(0, 1);
  CommonOptions run_options, bench_options, widths_options;
  std::string json_path;
  double bench_seconds = 1.0;

  CLI::App* run = app.add_subcommand("run", "run a scene through the designs (the default command)");
  add_common(run, run_options);
  run->add_option("--json", json_path, "also write the results as JSON to this file");
  bool show_worst = false;
  run->add_flag("--worst", show_worst, "print each design's worst pixel");

  CLI::App* bench = app.add_subcommand("bench", "model throughput per design, in M pixels/s");
  add_common(bench, bench_options);
  bench->add_option("--seconds", bench_seconds, "minimum time per design")->check(CLI::PositiveNumber);

  CLI::App* widths = app.add_subcommand("widths", "list the width and microarchitecture parameters");
  widths->add_option("--set", widths_options.settings, "NAME=VALUE, as for run");
  std::string sv_path;
  widths->add_option("--sv", sv_path,
                     "write the RTL's cd_widths.svh (parameters, derived widths, flags, word "
                     "layout) to this file, or - for stdout");

  CLI::App* regress = cdsim::rtl::add_regress_command(app);
  SweepOptions sweep_options;
  CLI::App* sweep = add_sweep_command(app, sweep_options);
  CLI::App* designs = app.add_subcommand("designs", "list the designs");
  CLI::App* hard = app.add_subcommand("hard-cases", "list the named hard cases (--scene hard:NAME, hard:all)");
  RenderOptions render_options;
  CLI::App* render = add_render_command(app, render_options);
  SizeOptions size_options;
  CLI::App* size = add_size_command(app, size_options);
  AreaOptions area_options;
  CLI::App* area = add_area_command(app, area_options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (*bench) return bench_command(bench_options, bench_seconds);
    if (*widths) return widths_command(widths_options, sv_path);
    if (*regress) return cdsim::rtl::run_regress_command();
    if (*sweep) return run_sweep_command(sweep_options);
    if (*render) return run_render_command(render_options);
    if (*size) return run_size_command(size_options);
    if (*area) return run_area_command(area_options);
    if (*hard) {
      for (const HardCase& c : hard_cases()) fmt::print("hard:{:<15} {}\n", c.name, c.expected);
      return 0;
    }
    if (*designs) {
      for (const Design& d : all_designs()) fmt::print("{:<17} {}\n", d.name, d.summary);
      return 0;
    }
    return run_command(run_options, json_path, show_worst);
  } catch (const std::exception& e) {
    fmt::print(stderr, "cdsim: error: {}\n", e.what());
    return 2;
  }
}
