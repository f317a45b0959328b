// `cdsim regress`: the triangles (a scene or seeded random ones), the widths
// (a named configuration, or any widths with --set), the unit (every design's
// hardware, or only the chosen designs'), verilated on first use into a cache
// by rtl_cache.cpp, and the one bench of bench.hpp that runs the
// Verilated scan unit against the C++ model.
#include "regress.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <systemc.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>
#include <memory>
#include <tuple>

#include "bench.hpp"  // BenchOptions, BenchSummary
#include "evaluate.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "random_triangles.hpp"
#include "rtl_coverage.hpp"
#include "rtl_cache.hpp"
#include "scene.hpp"
#include "scoreboard.hpp"
#include "shard.hpp"
#include "cache_files.hpp"
#include "child_process.hpp"
#include "report.hpp"

// SystemC's library refers to sc_main; cdsim has its own main and starts the
// kernel itself, so this one is never called.
int sc_main(int, char**) { return 1; }

namespace cdsim::rtl {

namespace {

RegressOptions options;  // of the run in progress

struct WidthConfig {
  const char* name;
  const char* settings;  // overrides of model/widths.def, "name=value ..."
};
const WidthConfig kConfigs[] = {
#define X(name, settings) {#name, settings},
#include "rtl_configs.def"
#undef X
};

}  // namespace

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
    // Every design of the scan unit; the adaptive design has a unit of its own.
    for (const Design& d : all_designs())
      if (has_rtl(d) && rtl_top(d) == RtlTop::ScanUnit) out.push_back(&d);
    return out;
  }
  // One design, or a comma-separated list taken in turn like mix.
  for (const Design& listed : parse_design_list(name)) {
    const Design& d = find_design(listed.name);
    if (!has_rtl(d))
      throw std::invalid_argument(fmt::format(
          "design '{}' has no RTL yet; the RTL implements {} (or 'mix': each in turn)", d.name,
          rtl_design_names()));
    out.push_back(&d);
  }
  for (const Design* d : out)
    if (rtl_top(*d) != rtl_top(*out.front()))
      throw std::invalid_argument(fmt::format(
          "--design {}: {} and {} are different units (rtl/adaptive_unit.sv, rtl/cd_scan_unit.sv); "
          "regress them one at a time",
          name, out.front()->name, d->name));
  return out;
}

namespace {

// add_regress_command: app/regress_cli.cpp.

// InterruptWatch looks at the interrupt flag every 100 us of simulated time
// (10,000 periods of the bench's 10 ns clock: milliseconds of wall time).
constexpr int kInterruptPollNs = 100'000;

// Pauses the simulation when SIGINT or SIGTERM arrives; regress() then stops
// with Interrupted. The bench closes the waveform as at any other end.
SC_MODULE(InterruptWatch) {
  SC_CTOR(InterruptWatch) { SC_THREAD(watch); }
  void watch() {
    while (true) {
      wait(sc_core::sc_time(kInterruptPollNs, sc_core::SC_NS));
      if (interrupted()) sc_core::sc_pause();
    }
  }
};

// The bench's hang limit for each job, from the model's run of the job.
std::vector<int64_t> hang_limits(const std::vector<Job>& jobs, const Widths& widths,
                                 double backpressure) {
  std::map<UnitKey, std::unique_ptr<ScanUnit>> units;
  std::vector<Fragment> fragments;
  std::vector<int64_t> limits;
  limits.reserve(jobs.size());
  for (const Job& job : jobs) {
    throw_if_interrupted();
    auto& unit = units[unit_key(job)];
    if (!unit)
      unit = std::make_unique<ScanUnit>(*job.design, widths, job.viewport_width, job.viewport_height);
    unit->set_viewport(job.viewport_width, job.viewport_height);
    fragments.clear();
    const TriangleRecord record = unit->run(job.triangle, &fragments);
    // Its clocks on this design's own schedule, plus a setup: at most what it
    // takes from the last record to its own in any stream.
    limits.push_back(hang_cycle_limit(record.cycles + unit->timing().setup_cycles(), record.pixels, backpressure));
  }
  return limits;
}

// The folder of an output file (--trace, --json) must exist and be writable
// before minutes of simulation.
void check_output_path(const std::string& option, const std::string& path) {
  if (path.empty()) return;
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(path).parent_path();
  std::error_code ignored;
  if (!folder.empty() && !fs::is_directory(folder, ignored))
    throw std::invalid_argument(fmt::format("{} {}: the folder {} does not exist", option, path, folder.string()));
  if (fs::is_directory(path, ignored)) throw std::invalid_argument(fmt::format("{} {}: is a folder", option, path));
  // The waveform is written by the FST library, which seeks and renames:
  // it goes beside and is renamed over, so only a regular file can take it.
  if (option == "--trace") check_regular_output(option, path);
  if (::access(folder.empty() ? "." : folder.c_str(), W_OK) != 0)
    throw std::invalid_argument(fmt::format("{} {}: cannot write into {}: {}", option, path,
                                            folder.empty() ? "." : folder.string(), std::strerror(errno)));
}

}  // namespace

std::vector<Job> source_jobs(const RegressOptions& o, const Widths& widths,
                             const std::vector<const Design*>& designs, std::string& source) {
  std::vector<Job> jobs;
  if (o.random > 0 && !o.scene_and_random) {
    jobs = random_jobs(o.random, o.seed, widths, designs);
    source = fmt::format("{} random triangles (seed {})", o.random, o.seed);
    std::cout << "source: " << source << '\n';
  } else {
    std::vector<std::string> names = {o.scene};
    names.insert(names.end(), o.more_scenes.begin(), o.more_scenes.end());
    for (const std::string& name : names) {
      const PreparedScene scene = prepare(load_scene(name, o.scene_options), widths);
      for (size_t i = 0; i < scene.unit.size(); ++i) {
        Job job;
        job.triangle = scene.unit[i];
        job.design = designs[jobs.size() % designs.size()];
        job.viewport_width = scene.scene.width;
        job.viewport_height = scene.scene.height;
        job.origin = fmt::format("scene {} triangle {}", scene.scene.name, i);
        jobs.push_back(std::move(job));
      }
      const std::string one = fmt::format("scene {} ({} triangles, {}x{})", scene.scene.name, scene.unit.size(),
                                          scene.scene.width, scene.scene.height);
      std::cout << (source.empty() ? "source: " : "source: then ") << one << '\n';
      source += (source.empty() ? "" : ", then ") + one;
    }
  }
  if (o.random > 0 && o.scene_and_random) {
    for (Job& job : random_jobs(o.random, o.seed, widths, designs))
      jobs.push_back(std::move(job));
    std::cout << fmt::format("source: then {} random triangles (seed {})\n", o.random,
                             o.seed);
    source += fmt::format(", then {} random triangles (seed {})", o.random, o.seed);
  }
  for (size_t i = 0; i < jobs.size(); ++i) jobs[i].number = i;
  return jobs;
}

namespace {

// The named configuration with exactly these widths, or "" if none.
std::string builtin_config_of(const Widths& widths) {
  for (const auto& c : kConfigs)
    if (describe(widths_of(c.name)) == describe(widths)) return c.name;
  return "";
}

// Runs the bench at the widths of `options`: a named configuration, one with
// --set on top, or exactly `given` (size --verify), on the RTL verilated for
// them (and the unit's parameters) into the cache.
int regress(const Widths* given) {
  Widths widths = given ? *given : widths_of(options.widths);
  apply_settings(widths, options.settings);
  validate(widths);
  check_output_path("--trace", options.trace);
  check_output_path("--json", options.json_path);
  {
    std::vector<NamedFile> inputs;
    std::vector<std::string> scenes = {options.scene};
    scenes.insert(scenes.end(), options.more_scenes.begin(), options.more_scenes.end());
    if (options.random == 0 || options.scene_and_random)
      for (const std::string& scene : scenes) inputs.push_back({"--scene", scene_input_file(scene)});
    check_distinct_files({{"--trace", options.trace}, {"--json", options.json_path}}, inputs);
  }
  const bool exact = given || !options.settings.empty();
  const std::string builtin = exact ? builtin_config_of(widths) : options.widths;
  std::string label = given ? "as sized" : options.widths;
  if (!options.settings.empty()) label += " with";
  for (const std::string& s : options.settings) label += " " + s;
  if (exact && !builtin.empty()) label += fmt::format(" (= the '{}' configuration)", builtin);
  const std::vector<const Design*> designs = designs_for(options.design);
  std::cout << fmt::format("regress: seed {}\n", options.seed);
  std::string source;
  std::vector<Job> jobs = source_jobs(options, widths, designs, source);
  const size_t source_triangles = jobs.size();
  const Shard shard = options.shard.empty() ? Shard{} : parse_shard("--shard", options.shard);
  if (!shard.whole()) {
    if (options.only >= 0) throw std::invalid_argument("--shard and --only: give one of them");
    std::vector<Job> held;
    for (Job& job : jobs)
      if (shard.holds(job.number)) held.push_back(std::move(job));
    jobs = std::move(held);
    std::cout << fmt::format("shard {}/{}: {} of the {} triangles\n", shard.index, shard.count, jobs.size(),
                             source_triangles);
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
  BenchOptions bench_options;
  bench_options.seed = options.seed;
  bench_options.backpressure = options.backpressure;
  // Written beside and renamed into place at the end, as --json is: an
  // interrupted run leaves no partial waveform, a device is never replaced.
  const std::filesystem::path trace_temporary =
      options.trace.empty() ? std::filesystem::path() : temporary_beside(options.trace);
  RemoveOnExit remove_trace(trace_temporary);
  bench_options.trace = trace_temporary.string();
  bench_options.trace_name = options.trace;
  bench_options.cycle_limits = hang_limits(jobs, widths, options.backpressure);
  BenchSummary summary;
  bench_options.summary = &summary;
  // Progress on stderr (a bar on a terminal, else a line every 5 s), looked
  // at every 64 triangles and redrawn at most 5 times a second.
  Progress progress(jobs.size(), "regress", "triangles");
  const auto start = std::chrono::steady_clock::now();
  double next_draw = 0;
  bool drawn = false, ended = false;
  bench_options.on_record = [&](size_t done) {
    const bool last = done == jobs.size();
    if (done % 64 != 0 && !last) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (seconds < next_draw && !last) return;
    next_draw = seconds + 0.2;
    drawn = true;
    ended = last;
    progress.update(done, seconds, last);
  };
  std::cout << fmt::format(
      "hang limit: 4 x (model cycles + pixels x p / (1 - p)) + 1000 per triangle, at most {}\n",
      bench_options.cycle_limits.empty()
          ? int64_t{0}
          : *std::max_element(bench_options.cycle_limits.begin(), bench_options.cycle_limits.end()));
  std::cout.flush();
  // A coverage run takes a coverage build.
  const bool coverage = !options.coverage_dir.empty();
  const CoverageBuild coverage_build = !coverage                ? CoverageBuild::None
                                       : options.coverage_toggle ? CoverageBuild::All
                                                                 : CoverageBuild::Lines;
  if (coverage) {
    bench_options.coverage = coverage_data_path(options.coverage_dir,
                                                describe(widths) + (options.coverage_toggle ? "" : " no-toggle"),
                                                source, options.design,
                                                options.backpressure, options.shard, options.only);
  }
  const bool adaptive = rtl_top(*designs.front()) == RtlTop::AdaptiveUnit;
  // The unit with only these designs' hardware, unless that is every design's,
  // or the run measures coverage (of the whole unit's RTL, merged across runs).
  std::vector<UnitParameter> parameters;
  if (!adaptive && !options.whole_unit && !coverage) {
    const std::vector<UnitParameter> own = unit_parameters(designs), whole = unit_parameters(designs_for("mix"));
    const auto same = [](const UnitParameter& a, const UnitParameter& b) {
      return std::string(a.name) == b.name && a.value == b.value;
    };
    if (!std::equal(own.begin(), own.end(), whole.begin(), whole.end(), same)) parameters = own;
  }
  std::cout << fmt::format("unit: {}\n", parameters.empty() ? std::string("every design's hardware")
                                                           : "only these designs' hardware (" + unit_parameter_list(parameters) + ")");
  for (const UnitParameter& p : parameters)
    if (std::string(p.name) == "HasTable") bench_options.unit_has_table = p.value != 0;
  const RunBench run_unit = load_custom_rtl(widths, options.rtl_cache, coverage_build, adaptive, parameters);
  InterruptWatch watch("interrupt_watch");
  const int status = run_unit(&jobs, &widths, &bench_options);
  throw_if_interrupted();
  if (drawn && !ended)  // a run that stopped early ends its bar too
    progress.update(static_cast<size_t>(std::max<int64_t>(0, summary.triangles)),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), true);
  if (!options.trace.empty()) {
    if (!std::filesystem::exists(trace_temporary))
      throw std::runtime_error(fmt::format("--trace {}: the waveform was not written", options.trace));
    publish_file(trace_temporary, options.trace);
    remove_trace.release();
  }
  if (coverage) {
    std::cout << fmt::format("coverage data: {}\n", bench_options.coverage);
    report_coverage(options.coverage_dir);
  }
  if (!options.json_path.empty()) {
    nlohmann::json flags = nlohmann::json::object();
    for (const auto& [name, count] : summary.flags) flags[name] = count;
    nlohmann::json j = {
        {"kind", "cdsim regress"}, {"build", build_id()}, {"seed", options.seed},
        {"source", source}, {"source_triangles", source_triangles}, {"widths", describe(widths)},
        {"design", options.design}, {"backpressure", options.backpressure},
        {"triangles", summary.triangles}, {"fragments", summary.fragments},
        {"mismatches", summary.mismatches}, {"hangs", summary.hangs}, {"rtl_cycles", summary.rtl_cycles},
        {"model_cycles", summary.model_cycles}, {"clocks", summary.clocks},
        {"model_clocks", summary.model_clocks}, {"setups_compared", summary.setups},
        {"table_writes_compared", summary.table_writes}, {"y_major_triangles", summary.y_major},
        {"flags", flags}, {"failed_triangles", summary.failed}};
    if (!shard.whole()) j["shard"] = {{"index", shard.index}, {"count", shard.count}};
    if (options.only >= 0) j["only"] = options.only;
    write_file_atomic(options.json_path, j.dump(2) + "\n");
    std::cout << fmt::format("wrote {}\n", options.json_path);
  }
  return status;
}

}  // namespace

int64_t hang_cycle_limit(int64_t model_cycles, int64_t pixels, double backpressure) {
  const double expected_stalls = double(pixels) * backpressure / (1.0 - backpressure);
  return 4 * (model_cycles + static_cast<int64_t>(std::ceil(expected_stalls))) + 1000;
}

int run_regress_command(const RegressOptions& given) {
  options = given;
  if (options.then_random > 0) {
    options.scene_and_random = true;
    options.random = options.then_random;
  }
  try {
    return regress(nullptr);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    throw_if_interrupted();  // a tool the RTL cache ran died of the same signal
    std::cerr << "cdsim regress: error: " << e.what() << '\n';
    return 2;
  }
}

namespace {

// The RTL check in request.jobs shards at once: each a child `cdsim regress
// --shard I/N` of the same stream, at exactly these widths (every parameter
// --set), its output in a log and its summary in JSON; the summaries added up.
int verify_in_shards(const VerifyRequest& request) {
  namespace fs = std::filesystem;
  const unsigned count = request.jobs;
  const fs::path folder = fs::temp_directory_path() / fmt::format("cdsim-verify-{}", getpid());
  fs::remove_all(folder);
  fs::create_directories(folder);
  RemoveOnExit remove_folder(folder);
  std::vector<std::string> base = {fs::read_symlink("/proc/self/exe").string(), "regress",
                                   "--scene", request.scenes.front()};
  for (size_t i = 1; i < request.scenes.size(); ++i) base.insert(base.end(), {"--then-scene", request.scenes[i]});
  if (!request.scene_options.camera.empty()) base.insert(base.end(), {"--camera", request.scene_options.camera});
  if (request.scene_options.spawn >= 0)
    base.insert(base.end(), {"--spawn", std::to_string(request.scene_options.spawn)});
  if (!request.scene_options.resolution.empty())
    base.insert(base.end(), {"--resolution", request.scene_options.resolution});
  if (request.random > 0) base.insert(base.end(), {"--then-random", std::to_string(request.random)});
  base.insert(base.end(), {"--seed", std::to_string(request.seed), "--backpressure",
                           fmt::format("{}", request.backpressure), "--design", request.design});
  if (!request.rtl_cache.empty()) base.insert(base.end(), {"--rtl-cache", request.rtl_cache});
  std::istringstream settings(describe(request.widths));
  for (std::string setting; settings >> setting;) base.insert(base.end(), {"--set", setting});
  fmt::print("verify: {} shards at once (cdsim regress --shard I/{}; the first to start builds the unit)\n", count,
             count);
  std::fflush(stdout);
  std::vector<ChildCommand> shards;
  for (unsigned i = 0; i < count; ++i) {
    std::vector<std::string> argv = base;
    argv.insert(argv.end(), {"--shard", fmt::format("{}/{}", i + 1, count), "--json",
                             (folder / fmt::format("{}.json", i)).string()});
    shards.push_back({argv, folder / fmt::format("{}.log", i)});
  }
  const auto start = std::chrono::steady_clock::now();
  double next_line = 10;
  const std::vector<std::optional<int>> ended =
      run_children(shards, count, /*stop_at_failure=*/false, [&](double seconds, size_t done) {
        if (seconds < next_line) return;
        fmt::print(stderr, "verify: {} of {} shards done, {:.0f} s\n", done, count, seconds);
        next_line = seconds + 10;
      });
  std::vector<int> status;
  for (const std::optional<int>& s : ended) status.push_back(s.value_or(-1));
  // What the run was (the first shard's source, widths and unit: the same in
  // every shard), then each shard's share and summary.
  const auto lines_of = [&](unsigned i) {
    std::vector<std::string> lines;
    const fs::path log = folder / fmt::format("{}.log", i);
    std::string line;
    for (std::istringstream in(fs::exists(log) ? read_text_file(log) : std::string()); std::getline(in, line);)
      lines.push_back(line);
    return lines;
  };
  const auto starts = [](const std::string& line, const char* prefix) { return line.rfind(prefix, 0) == 0; };
  for (const std::string& line : lines_of(0))
    if (starts(line, "source:") || starts(line, "widths:") || starts(line, "design:") || starts(line, "unit:"))
      fmt::print("{}\n", line);
  for (unsigned i = 0; i < count; ++i)
    for (const std::string& line : lines_of(i))
      if (starts(line, "shard ") || line.find(" fragments compared, ") != std::string::npos) fmt::print("  {}\n", line);
  int64_t triangles = 0, fragments = 0, mismatches = 0, hangs = 0, rtl_cycles = 0, model_cycles = 0;
  int result = 0;
  for (unsigned i = 0; i < count; ++i) {
    const fs::path log = folder / fmt::format("{}.log", i), json = folder / fmt::format("{}.json", i);
    const bool exited = WIFEXITED(status[i]);
    if (!exited || WEXITSTATUS(status[i]) != 0 || !fs::exists(json)) {
      const std::vector<std::string> lines = lines_of(i);
      std::cerr << fmt::format("verify: shard {}/{} ended with {}; the end of its output:\n", i + 1, count,
                               describe_status(status[i]));
      for (size_t k = lines.size() > 30 ? lines.size() - 30 : 0; k < lines.size(); ++k) std::cerr << lines[k] << '\n';
      result = exited && WEXITSTATUS(status[i]) == 1 ? std::max(result, 1) : 2;
      if (!fs::exists(json)) continue;
    }
    const nlohmann::json j = nlohmann::json::parse(read_text_file(json));
    triangles += j.at("triangles").get<int64_t>();
    fragments += j.at("fragments").get<int64_t>();
    mismatches += j.at("mismatches").get<int64_t>();
    hangs += j.at("hangs").get<int64_t>();
    rtl_cycles += j.at("rtl_cycles").get<int64_t>();
    model_cycles += j.at("model_cycles").get<int64_t>();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("verify: {} triangles in {} shards, {} fragments compared, {} mismatches, {} hangs, RTL cycles {}, "
             "model cycles {}, {:.0f} s\n",
             triangles, count, fragments, mismatches, hangs, rtl_cycles, model_cycles, seconds);
  if (result == 0 && (mismatches > 0 || hangs > 0)) result = 1;
  return result;
}

}  // namespace

int verify_widths(const VerifyRequest& request) {
  if (request.scenes.empty()) throw std::invalid_argument("verify: no scene");
  if (request.jobs > 1) return verify_in_shards(request);
  options = RegressOptions{};
  if (request.scenes.empty()) throw std::invalid_argument("verify: no scene");
  options.scene = request.scenes.front();
  options.more_scenes.assign(request.scenes.begin() + 1, request.scenes.end());
  options.scene_options = request.scene_options;
  options.scene_and_random = true;
  options.random = request.random;
  options.seed = request.seed;
  options.backpressure = request.backpressure;
  options.design = request.design;
  options.rtl_cache = request.rtl_cache;
  try {
    return regress(&request.widths);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    throw_if_interrupted();
    std::cerr << "cdsim: RTL check: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace cdsim::rtl
