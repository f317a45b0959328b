// cdsim: command-line front of the constant-depth scan unit simulator.
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <iterator>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <thread>

#include "area.hpp"
#include "cache_files.hpp"
#include "cli.hpp"
#include "common.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "render.hpp"
#include "size.hpp"
#include "sweep.hpp"
#include "evaluate.hpp"
#include "flagged_triangles.hpp"
#include "exact.hpp"
#include "hard_cases.hpp"
#include "regress.hpp"
#include "report.hpp"
#include "loaders/scene_cli.hpp"
#include "scene.hpp"
#include "derived_widths.hpp"
#include "widths.hpp"

namespace {

using namespace cdsim;

// Every fragment of one design as CSV: the output u, v as numbers (exact in
// binary: integers over 2^out_frac), the exact reference's, and flag names.
class FragmentDump {
 public:
  explicit FragmentDump(int out_frac) : scale_(std::ldexp(1.0, -out_frac)) {
    fmt::format_to(std::back_inserter(text_), "triangle,x,y,u,v,exact_u,exact_v,flags\n");
  }
  void add(int64_t triangle, const Fragment& f, const ExactSample& exact) {
    std::string flags;
    for (int bit = 0; bit < flag::kCount; ++bit)
      if ((f.flags >> bit) & 1) flags += (flags.empty() ? "" : "|") + std::string(flag::name(bit));
    fmt::format_to(std::back_inserter(text_), "{},{},{},{},{},{},{},{}\n", triangle, f.x, f.y,
                   static_cast<double>(f.u) * scale_, static_cast<double>(f.v) * scale_,
                   static_cast<double>(exact.u), static_cast<double>(exact.v), flags);
  }
  std::string text() const { return fmt::to_string(text_); }

 private:
  double scale_;
  fmt::memory_buffer text_;
};

int run_command(const CommonOptions& options, const std::string& json_path, bool show_worst,
                bool with_area, const std::string& area_flow, const std::string& dump_path,
                const std::string& flagged_path, unsigned jobs) {
  const Widths widths = widths_from(options);
  const std::vector<Design> designs = designs_from(options.designs);
  if (!json_path.empty()) check_output_folder("--json", json_path);
  if (!dump_path.empty()) check_output_folder("--dump", dump_path);
  if (!flagged_path.empty()) check_output_folder("--flagged", flagged_path);
  check_distinct_files({{"--json", json_path}, {"--dump", dump_path}, {"--flagged", flagged_path}},
                       {{"--scene", scene_input_file(options.scene)}});
  const PreparedScene scene = prepare(load_scene(options.scene, options.scene_options), widths);
  std::cout << provenance(scene.scene, widths) << std::endl;  // before the long part
  // The designs in parallel, `jobs` at a time (each evaluate() is independent);
  // the dump is the first design's, and each design tallies its own flagged
  // triangles, joined in the designs' order.
  std::vector<DesignResult> results(designs.size());
  FragmentDump dump(widths.out_frac);
  std::vector<FlaggedTriangles> flagged_of(designs.size(), FlaggedTriangles(scene, widths));
  // Fewer designs than cores: each measures its error on the cores left.
  const unsigned cores = jobs > 0 ? jobs : std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads = std::max<unsigned>(1, cores / static_cast<unsigned>(designs.size()));
  run_parallel(designs.size(), jobs, "run", "designs", [&](size_t i) {
    const bool dumped = !dump_path.empty() && i == 0, tallied = !flagged_path.empty();
    FlaggedTriangles& flagged = flagged_of[i];
    const FragmentVisitor visit = [&](int64_t t, const Fragment& f, const ExactSample& x) {
      if (dumped) dump.add(t, f, x);
      if (tallied) flagged.add(t, f, x);
    };
    if (tallied) flagged.start(designs[i]);
    results[i] = evaluate(scene, designs[i], widths, true, dumped || tallied ? &visit : nullptr, threads);
    if (tallied) flagged.finish();
  });
  FlaggedTriangles flagged(scene, widths);
  for (FlaggedTriangles& f : flagged_of) flagged.append(std::move(f));
  std::cout << results_table(results, widths);
  std::cout << cycle_breakdown_table(results);
  if (show_worst) std::cout << worst_pixels(results, scene.scene, widths);
  if (!flagged_path.empty()) std::cout << flagged.table(10);
  nlohmann::json json = results_json(scene.scene, widths, results);
  if (with_area) {
    AreaOptions area_options;
    area_options.flow = area_flow;
    std::vector<AreaJob> syntheses;
    for (const Design& d : designs)
      if (has_rtl(d)) syntheses.push_back({d, widths});
    std::fflush(stdout);
    const std::vector<AreaReport> areas = synthesise_areas(syntheses, area_options, jobs);
    std::vector<double> px_per_clk;
    for (const DesignResult& r : results)
      if (has_rtl(r.design)) px_per_clk.push_back(r.pixels_per_clock());
    std::cout << '\n' << area_table(areas, area_options, px_per_clk);
    std::string missing;
    for (const Design& d : designs)
      if (!has_rtl(d)) missing += (missing.empty() ? "" : ", ") + d.name;
    if (!missing.empty()) std::cout << "no RTL, so no area: " << missing << '\n';
    for (size_t i = 0, a = 0; i < designs.size(); ++i)
      if (has_rtl(designs[i])) {
        const nlohmann::json rates = area_summary_json(areas[a], results[i].pixels_per_clock());
        json["designs"][i]["area"] = area_json(areas[a++], area_options);
        for (const char* key : {"px_per_clk", "mpix_per_s", "um2_per_mpix_per_s"})
          json["designs"][i]["area"][key] = rates.at(key);
      } else {
        json["designs"][i]["area"] = nlohmann::json();
      }
  }
  if (!json_path.empty()) {
    write_file_atomic(json_path, json.dump(2) + '\n');
    std::cout << "wrote " << json_path << '\n';
  }
  if (!dump_path.empty()) {
    write_file_atomic(dump_path, dump.text());
    std::cout << fmt::format("wrote {} ({} fragments of {})\n", dump_path, results.front().pixels,
                             results.front().design.name);
  }
  if (!flagged_path.empty()) {
    write_file_atomic(flagged_path, flagged.csv());
    std::cout << fmt::format("wrote {} ({} flagged triangles)\n", flagged_path, flagged.size());
  }
  return 0;
}

int bench_command(const CommonOptions& options, double seconds) {
  const Widths widths = widths_from(options);
  const std::vector<Design> designs = designs_from(options.designs);
  const PreparedScene scene = prepare(load_scene(options.scene, options.scene_options), widths);
  std::cout << provenance(scene.scene, widths);
  fmt::print("single-threaded model throughput, error measurement off, at least {} s per design\n\n",
             seconds);
  std::fflush(stdout);
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
    if (sv_path != "-") check_output_folder("--sv", sv_path);
    const std::string text = rtl_header(widths, "custom");
    if (sv_path == "-") {
      std::cout << text;
      return 0;
    }
    write_file_atomic(sv_path, text);
    std::cout << "wrote " << sv_path << '\n';
    return 0;
  }
  fmt::print("{:<18} {:>7} {:>7} {:>7}  {}\n", "parameter", "value", "min", "max", "meaning");
  for (const auto& p : param_table())
    fmt::print("{:<18} {:>7} {:>7} {:>7}  {}\n", p.name, widths.*(p.field), p.min_value,
               p.max_value, p.meaning);
  // A range of widths.def that the other parameters narrow (validate's
  // checks across parameters), with the reason at the first value refused.
  std::string narrower;
  for (const auto& p : param_table()) {
    const int value = widths.*(p.field);
    const auto refusal = [&](int v) -> std::string {
      Widths trial = widths;
      trial.*(p.field) = v;
      try {
        validate(trial);
        return "";
      } catch (const std::invalid_argument& e) {
        return e.what();
      }
    };
    int lo = value, hi = value;
    std::string below, above;
    while (lo > p.min_value && (below = refusal(lo - 1)).empty()) --lo;
    while (hi < p.max_value && (above = refusal(hi + 1)).empty()) ++hi;
    if (lo > p.min_value)
      narrower += fmt::format("  {} at least {} here, not {}: {}={}: {}\n", p.name, lo, p.min_value, p.name, lo - 1, below);
    if (hi < p.max_value)
      narrower += fmt::format("  {} at most {} here, not {}: {}={}: {}\n", p.name, hi, p.max_value, p.name, hi + 1, above);
  }
  if (!narrower.empty())
    fmt::print("\nranges that the other parameters' values narrow (--set them to widen):\n{}", narrower);
  const DerivedWidths derived = derive(widths);
  fmt::print("\n{:<24} {:>7}  {}\n", "derived (RTL)", "value", "meaning");
  for (const auto& p : derived_table())
    fmt::print("{:<24} {:>7}  {}\n", p.name, derived.*(p.field), p.meaning);
  return 0;
}

// Runs the parsed command; returns its exit status.
// Each design of model/designs.def with what the tools read from it.
nlohmann::json designs_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const Design& d : all_designs())
    out.push_back({{"name", d.name},
                   {"summary", d.summary},
                   {"kind", kind_name(d.kind)},
                   {"density", d.density},
                   {"correction", d.correction},
                   {"pipelined", d.pipelined},
                   {"subdivision", d.subdivision},
                   {"persp", d.persp},
                   {"quadratic", d.quadratic},
                   {"fallback", d.fallback},
                   {"rtl", has_rtl(d)},
                   {"unit_parameters", has_rtl(d) && rtl_top(d) == RtlTop::ScanUnit
                                           ? unit_parameter_list(unit_parameters({&d}))
                                           : ""},
                   {"sized_widths", d.sized_widths},
                   {"sweep_axes", d.sweep_axes},
                   {"sweep_grid", d.sweep_grid}});
  return out;
}

int dispatch(Cli& cli) {
  if (*cli.bench_command) return bench_command(cli.bench, cli.bench_seconds);
  if (*cli.widths_command) return widths_command(cli.widths, cli.sv_path);
  if (*cli.regress_command) return cdsim::rtl::run_regress_command(cli.regress);
  if (*cli.coverage_command) return cdsim::rtl::run_coverage_command(cli.coverage);
  if (*cli.vectors_command) return cdsim::rtl::run_vectors_command(cli.vectors);
  if (*cli.sweep_command) return run_sweep_command(cli.sweep);
  if (*cli.merge_command) return run_merge_command(cli.merge);
  if (*cli.render_command) return run_render_command(cli.render);
  if (*cli.size_command) return run_size_command(cli.size);
  if (*cli.area_command) return run_area_command(cli.area);
  if (*cli.choose_command) return run_choose_command(cli.choose);
  if (*cli.area_model_command) return run_area_model_command(cli.area_model);
  if (*cli.hard_cases_command) {
    for (const HardCase& c : hard_cases()) fmt::print("hard:{:<15} {}\n", c.name, c.expected);
    return 0;
  }
  if (*cli.designs_command) {
    for (const Design& d : all_designs())
      fmt::print("{:<17} {}{}\n", d.name, d.summary, has_rtl(d) ? "" : " [model only: no RTL yet]");
    if (!cli.designs_json_path.empty()) write_file_atomic(cli.designs_json_path, designs_json().dump(2) + '\n');
    return 0;
  }
  return run_command(cli.run, cli.json_path, cli.show_worst, cli.run_area, cli.run_area_flow, cli.dump_path, cli.flagged_path,
                     static_cast<unsigned>(cli.run_jobs));
}

// What was printed must have reached stdout: a full disk or a closed file is
// an error too, as coreutils' close_stdout makes it.
int check_stdout(int status) {
  errno = 0;
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    fmt::print(stderr, "cdsim: error: stdout: cannot write{}\n",
               errno ? fmt::format(": {}", std::strerror(errno)) : "");
    return status != 0 ? status : 2;
  }
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  install_interrupt_handlers();
  const std::unique_ptr<Cli> cli = make_cli();
  try {
    cli->app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli->app.exit(e);
  }
  int status = 0;
  try {
    status = dispatch(*cli);
  } catch (const Interrupted& e) {
    std::cout.flush();
    fmt::print(stderr, "cdsim: {}\n", e.what());
    return e.exit_status();
  } catch (const std::exception& e) {
    std::cout.flush();
    fmt::print(stderr, "cdsim: error: {}\n", e.what());
    return check_stdout(2);
  }
  return check_stdout(status);
}
