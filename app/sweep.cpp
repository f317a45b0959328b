#include "sweep.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>

#include "area.hpp"
#include "cache_files.hpp"
#include "cli_checks.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "report.hpp"

namespace cdsim {

namespace {

struct Config {
  Design design;
  Widths widths;
  std::vector<std::pair<std::string, int>> swept;
};

// Every combination of the axes, for every design.
std::vector<Config> product_configs(const std::vector<Design>& designs,
                                    const std::vector<SweepAxis>& axes) {
  std::vector<Config> configs;
  configs.reserve(size_t(sweep_size(designs.size(), axes)));
  for (const Design& d : designs) {
    std::vector<size_t> index(axes.size(), 0);
    while (true) {
      Config c{d, Widths{}, {}};
      for (size_t a = 0; a < axes.size(); ++a) {
        set_param(c.widths, axes[a].name, axes[a].values[index[a]]);
        if (axes[a].values.size() > 1) c.swept.emplace_back(axes[a].name, axes[a].values[index[a]]);
      }
      configs.push_back(c);
      size_t a = 0;
      for (; a < axes.size(); ++a) {
        if (++index[a] < axes[a].values.size()) break;
        index[a] = 0;
      }
      if (a == axes.size()) break;
    }
  }
  return configs;
}

// The default sweep: for each design, one-dimensional sweeps of the widths
// that decide its accuracy, around the defaults (251 configurations).
std::vector<Config> default_configs() {
  const std::vector<SweepAxis> constant_depth = {
      {"g_frac", {6, 8, 10, 12, 14, 16, 18, 20}},
      {"s_frac", {8, 10, 12, 14, 16, 18, 20, 22, 24}},
      {"out_frac", {2, 4, 6, 8, 10, 12}}};
  const std::vector<SweepAxis> correction = {{"d_frac", {2, 4, 6, 8, 10, 12}}};
  const std::vector<SweepAxis> divide = {{"recip_bits", {8, 10, 12, 14, 16, 18, 20, 22, 24}},
                                         {"out_frac", {2, 4, 6, 8, 10, 12}}};
  // Kim-style: the full grid of fraction bits and unrolling, so that its
  // Pareto front is its best at every error level.
  const std::vector<SweepAxis> kim = {{"kim_frac", {1, 2, 3, 4, 6, 8, 10, 12}},
                                      {"kim_unroll", {1, 2, 4, 8}}};
  const std::vector<SweepAxis> affine = {{"s_frac", {8, 10, 12, 14, 16, 18, 20, 22, 24}},
                                         {"out_frac", {2, 4, 6, 8, 10, 12}}};
  std::vector<Config> configs;
  for (const Design& d : all_designs()) {
    std::vector<SweepAxis> axes;
    switch (d.kind) {
      case Design::Kind::ConstantDepth:
        axes = constant_depth;
        if (d.correction) axes.insert(axes.end(), correction.begin(), correction.end());
        break;
      case Design::Kind::Divide: axes = divide; break;
      case Design::Kind::Kim: {
        for (const Config& c : product_configs({d}, kim)) configs.push_back(c);
        continue;
      }
      case Design::Kind::Affine: axes = affine; break;
    }
    for (const SweepAxis& axis : axes)
      for (int value : axis.values) {
        Config c{d, Widths{}, {{axis.name, value}}};
        set_param(c.widths, axis.name, value);
        configs.push_back(c);
      }
  }
  return configs;
}

// A CSV field, quoted when it holds a separator, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string csv_header() {
  std::string h = "scene,design";
  for (const auto& p : param_table()) h += fmt::format(",{}", p.name);
  h += ",swept,pixels,cycles,pixels_per_clock,table_entries,table_bits,register_bits,error_mean,"
       "error_rms,error_p99,error_max,footprint_max,texel_mismatch,over_lsb,flagged_triangles";
  // Empty unless the sweep ran with --area and the design has RTL.
  h += ",logic_area_um2,nand2_eq,sram_bits,sram_area_um2,flop_table_area_um2,total_area_um2";
  return h;
}

std::string swept_names(const Config& c) {
  std::string out;
  for (const auto& [name, value] : c.swept) out += (out.empty() ? "" : "+") + name;
  return out.empty() ? "-" : out;
}

int64_t flagged(const DesignResult& r) {
  int64_t n = 0;
  for (int bit = 0; bit < flag::kCount; ++bit)
    if (bit != 3) n += r.flagged_triangles[size_t(bit)];  // banding is not an error
  return n;
}

std::string csv_row(const std::string& scene, const Config& c, const DesignResult& r,
                    const AreaReport* area) {
  std::string row = fmt::format("{},{}", csv_field(scene), c.design.name);
  for (const auto& p : param_table()) row += fmt::format(",{}", c.widths.*(p.field));
  row += fmt::format(",{},{},{},{:.6f},{},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{}",
                     swept_names(c), r.pixels, r.cycles, r.pixels_per_clock(), r.table_depth,
                     r.table_bits, r.register_bits, r.error.mean, r.error.rms, r.error.p99,
                     r.error.max, r.error.footprint_max, r.error.texel_mismatch, r.error.over_lsb,
                     flagged(r));
  if (area) {
    const nlohmann::json a = area_summary_json(*area);
    row += fmt::format(",{:.1f},{:.1f},{},{:.1f},{:.1f},{:.1f}", area->logic_area_um2,
                       a.at("nand2_eq").get<double>(), area->sram_bits, area->sram_area_um2,
                       area->flop_table_area_um2, area->total_area_um2);
  } else {
    row += ",,,,,,";
  }
  return row;
}

// The sweep's axes and designs from --set, --design and --file; a parameter
// swept twice, or designs given twice, are refused naming both places.
struct Plan {
  bool default_sweep = false;
  std::vector<SweepAxis> axes;
  std::vector<Design> designs;
};

Plan make_plan(const SweepOptions& options) {
  Plan plan;
  std::map<std::string, std::string> origin;  // parameter -> where it is swept
  for (const std::string& setting : options.common.settings) {
    SweepAxis axis = parse_axis(setting);
    if (const auto it = origin.find(axis.name); it != origin.end())
      throw std::invalid_argument(
          fmt::format("{} and --set {} both sweep parameter {}; give it once", it->second, setting, axis.name));
    origin[axis.name] = "--set " + setting;
    plan.axes.push_back(std::move(axis));
  }
  std::string design_list = options.common.designs;
  if (!options.file.empty()) {
    std::error_code ignored;
    if (std::filesystem::is_directory(options.file, ignored))
      throw std::invalid_argument(fmt::format("--file {}: is a folder", options.file));
    std::ifstream in(options.file, std::ios::binary);
    if (!in)
      throw std::invalid_argument(fmt::format("--file {}: cannot open: {}", options.file, std::strerror(errno)));
    SweepFile file = parse_sweep_file(in, options.file);
    for (size_t i = 0; i < file.axes.size(); ++i) {
      if (const auto it = origin.find(file.axes[i].name); it != origin.end())
        throw std::invalid_argument(fmt::format("{}:{}: parameter {} is also swept by {}; give it once",
                                                options.file, file.axis_lines[i], file.axes[i].name,
                                                it->second));
      plan.axes.push_back(std::move(file.axes[i]));
    }
    if (!file.designs.empty()) {
      if (!design_list.empty())
        throw std::invalid_argument(fmt::format(
            "{}:{}: 'design {}' and --design {} both choose the designs; give one",
            options.file, file.design_line, file.designs, design_list));
      design_list = file.designs;
    }
  }
  plan.default_sweep = plan.axes.empty() && design_list.empty();
  if (!plan.default_sweep) plan.designs = designs_from(design_list);
  return plan;
}

}  // namespace

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options) {
  CLI::App* sweep = app.add_subcommand(
      "sweep", "sweep widths and parameters for the designs, in parallel; writes sweep.csv and sweep.json");
  add_common(sweep, options.common);
  sweep->add_option("--file", options.file,
                    "sweep file: one NAME=LO:HI[:STEP] (or NAME=A,B,C, NAME=V) per line, "
                    "'design LIST', '#' comments");
  sweep->add_option("--out", options.out,
                    "output folder (created; locked while the sweep runs)")
      ->capture_default_str();
  sweep->add_option("--jobs", options.jobs, "worker threads (default: all cores)")
      ->check(cli::integer_in(1, 1024));
  sweep->add_flag("--area", options.area,
                  "also synthesise each distinct configuration of a design with RTL (cdsim area: "
                  "Yosys, cached, all cores) and add its area to the rows");
  sweep->add_flag("--yes", options.yes,
                  fmt::format("run a sweep of more than {} configurations", kSweepConfirmLimit));
  return sweep;
}

int run_sweep_command(const SweepOptions& options) {
  const Plan plan = make_plan(options);
  const uint64_t size = plan.default_sweep ? uint64_t(default_configs().size())
                                           : sweep_size(plan.designs.size(), plan.axes);
  const std::string count = size == UINT64_MAX ? fmt::format("more than {}", size) : fmt::format("{}", size);
  fmt::print("sweep: {} configurations x 1 scene ({}) = {} runs\n", count, options.common.scene, count);
  std::fflush(stdout);
  if (size > kSweepHardLimit)
    throw std::invalid_argument(fmt::format(
        "sweep of {} configurations: the limit is {} (each is held in memory); sweep fewer values",
        count, kSweepHardLimit));
  if (size > kSweepConfirmLimit && !options.yes)
    throw std::invalid_argument(fmt::format(
        "sweep of {} configurations is more than {}: narrow the ranges, or give --yes to run it",
        count, kSweepConfirmLimit));

  std::vector<Config> configs = plan.default_sweep ? default_configs() : product_configs(plan.designs, plan.axes);
  for (const Config& c : configs) validate(c.widths);

  // The folder is locked before the long part, so that a second sweep into it stops at once.
  std::error_code error;
  std::filesystem::create_directories(options.out, error);
  if (error)
    throw std::runtime_error(fmt::format("--out {}: cannot create the folder: {}", options.out, error.message()));
  const OutputFolderLock lock(options.out);

  const Scene scene = load_scene(options.common.scene, options.common.scene_options);
  const unsigned jobs = options.jobs > 0 ? unsigned(options.jobs)
                                         : std::max(1u, std::thread::hardware_concurrency());
  fmt::print("threads: {}\nscene: {} ({} triangles; {})\nbuild: {}\nseed: none (deterministic)\n",
             jobs, scene.name, scene.triangles.size(), scene.description, build_id());
  std::fflush(stdout);

  // Snapping depends on subpixel_bits and uv_in_frac: prepare once per pair.
  std::mutex prepared_mutex;
  std::map<std::pair<int, int>, std::shared_ptr<const PreparedScene>> prepared;
  const auto prepared_for = [&](const Widths& w) {
    std::lock_guard<std::mutex> guard(prepared_mutex);
    auto& slot = prepared[{w.subpixel_bits, w.uv_in_frac}];
    if (!slot) slot = std::make_shared<const PreparedScene>(prepare(scene, w));
    return slot;
  };
  prepared_for(configs.front().widths);  // refuse bad input before starting the workers

  std::vector<DesignResult> results(configs.size());
  std::atomic<size_t> next{0}, done{0};
  std::atomic<unsigned> running{jobs};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < jobs; ++t)
    workers.emplace_back([&] {
      for (size_t i; (i = next++) < configs.size();) {
        try {
          results[i] = evaluate(*prepared_for(configs[i].widths), configs[i].design, configs[i].widths);
        } catch (...) {
          std::lock_guard<std::mutex> guard(failure_mutex);
          if (!failure) failure = std::current_exception();
          next = configs.size();  // the others stop after their current configuration
        }
        ++done;
      }
      --running;
    });
  Progress progress(configs.size(), "sweep", "configurations");
  for (int tick = 0; running > 0; ++tick) {
    if (interrupted()) next = configs.size();
    if (tick % 2 == 0) progress.update(done, elapsed());
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (auto& w : workers) w.join();
  throw_if_interrupted();
  if (failure) std::rethrow_exception(failure);
  progress.update(done, elapsed(), true);

  // Area: each distinct configuration synthesised once, after the model runs.
  std::vector<std::optional<AreaReport>> areas(configs.size());
  if (options.area) {
    std::vector<AreaJob> jobs_list;
    std::vector<size_t> rows;
    for (size_t i = 0; i < configs.size(); ++i)
      if (has_rtl(configs[i].design)) {
        jobs_list.push_back({configs[i].design, configs[i].widths});
        rows.push_back(i);
      }
    fmt::print("area: {} configurations with RTL to synthesise (cached ones are free)\n", jobs_list.size());
    std::fflush(stdout);
    const AreaOptions area_options;
    const std::vector<AreaReport> reports = synthesise_areas(jobs_list, area_options, jobs);
    for (size_t k = 0; k < rows.size(); ++k) areas[rows[k]] = reports[k];
  }

  const std::string csv_path = (std::filesystem::path(options.out) / "sweep.csv").string();
  const std::string json_path = (std::filesystem::path(options.out) / "sweep.json").string();
  std::string csv = csv_header() + '\n';
  nlohmann::json json;
  json["scene"] = {{"name", scene.name}, {"description", scene.description},
                   {"triangles", scene.triangles.size()}, {"resolution", {scene.width, scene.height}}};
  json["build"] = build_id();
  json["seed"] = nullptr;
  for (const auto& p : param_table()) json["defaults"][p.name] = p.default_value;
  json["rows"] = nlohmann::json::array();
  for (size_t i = 0; i < configs.size(); ++i) {
    csv += csv_row(scene.name, configs[i], results[i], areas[i] ? &*areas[i] : nullptr) + '\n';
    nlohmann::json row = results_json(scene, configs[i].widths, {results[i]})["designs"][0];
    row["scene"] = scene.name;
    for (const auto& p : param_table()) row["widths"][p.name] = configs[i].widths.*(p.field);
    for (const auto& [name, value] : configs[i].swept) row["swept"][name] = value;
    if (areas[i]) row["area"] = area_summary_json(*areas[i]);
    json["rows"].push_back(row);
  }
  // Both files complete before either replaces the previous run's.
  write_files_atomic({{json_path, json.dump(1) + '\n'}, {csv_path, csv}});

  // A readable summary: per design, the range of cycles and the most accurate configuration.
  fmt::print("\n{:<17} {:>7} {:>11} {:>11} {:>10}  {}\n", "design", "configs", "min_cycles",
             "max_cycles", "best_mean", "best configuration");
  for (const Design& d : all_designs()) {
    int64_t lo = -1, hi = -1, n = 0;
    size_t best = configs.size();
    for (size_t i = 0; i < configs.size(); ++i) {
      if (configs[i].design.name != d.name) continue;
      ++n;
      lo = lo < 0 ? results[i].cycles : std::min(lo, results[i].cycles);
      hi = std::max(hi, results[i].cycles);
      if (best == configs.size() || results[i].error.mean < results[best].error.mean) best = i;
    }
    if (n == 0) continue;
    std::string setting;
    for (const auto& [name, value] : configs[best].swept) setting += fmt::format("{}={} ", name, value);
    fmt::print("{:<17} {:>7} {:>11} {:>11} {:>10.3e}  {}\n", d.name, n, lo, hi,
               results[best].error.mean, setting.empty() ? "defaults" : setting);
  }
  fmt::print("\n{} configurations in {:.1f} s; wrote {} and {}\n", configs.size(), elapsed(),
             csv_path, json_path);
  return 0;
}

}  // namespace cdsim
