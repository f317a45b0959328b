#include "sweep.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#include "report.hpp"

namespace cdsim {

namespace {

int parse_int(const std::string& text, const std::string& context) {
  size_t used = 0;
  int value = 0;
  try {
    value = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw std::invalid_argument(fmt::format("{}: '{}' is not an integer", context, text));
  return value;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t at = text.find(separator, start);
    parts.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

struct Config {
  Design design;
  Widths widths;
  std::vector<std::pair<std::string, int>> swept;
};

// Every combination of the axes, for every design.
std::vector<Config> product_configs(const std::vector<Design>& designs,
                                    const std::vector<SweepAxis>& axes) {
  std::vector<Config> configs;
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

std::string csv_header() {
  std::string h = "scene,design";
  for (const auto& p : param_table()) h += fmt::format(",{}", p.name);
  h += ",swept,pixels,cycles,pixels_per_clock,table_entries,table_bits,register_bits,error_mean,"
       "error_rms,error_p99,error_max,footprint_max,texel_mismatch,over_lsb,flagged_triangles";
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

std::string csv_row(const std::string& scene, const Config& c, const DesignResult& r) {
  std::string row = fmt::format("{},{}", scene, c.design.name);
  for (const auto& p : param_table()) row += fmt::format(",{}", c.widths.*(p.field));
  row += fmt::format(",{},{},{},{:.6f},{},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{}",
                     swept_names(c), r.pixels, r.cycles, r.pixels_per_clock(), r.table_depth,
                     r.table_bits, r.register_bits, r.error.mean, r.error.rms, r.error.p99,
                     r.error.max, r.error.footprint_max, r.error.texel_mismatch, r.error.over_lsb,
                     flagged(r));
  return row;
}

void progress(size_t done, size_t total, double seconds) {
  if (!isatty(fileno(stderr))) return;
  const int width = 40;
  const int filled = total ? int(width * done / total) : width;
  fmt::print(stderr, "\r[{:<{}}] {}/{} configurations, {:.0f} s", std::string(size_t(filled), '='),
             width, done, total, seconds);
  if (done == total) fmt::print(stderr, "\n");
}

}  // namespace

SweepAxis parse_axis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument(fmt::format("sweep setting '{}' is not NAME=LO:HI[:STEP], NAME=A,B or NAME=V", text));
  SweepAxis axis{text.substr(0, eq), {}};
  const std::string values = text.substr(eq + 1);
  if (values.find(':') != std::string::npos) {
    const auto parts = split(values, ':');
    if (parts.size() < 2 || parts.size() > 3)
      throw std::invalid_argument(fmt::format("sweep setting '{}': expected LO:HI or LO:HI:STEP", text));
    const int lo = parse_int(parts[0], text), hi = parse_int(parts[1], text);
    const int step = parts.size() == 3 ? parse_int(parts[2], text) : 1;
    if (step <= 0) throw std::invalid_argument(fmt::format("sweep setting '{}': STEP must be positive", text));
    if (hi < lo) throw std::invalid_argument(fmt::format("sweep setting '{}': HI is below LO", text));
    for (int v = lo; v <= hi; v += step) axis.values.push_back(v);
  } else {
    for (const auto& part : split(values, ',')) axis.values.push_back(parse_int(part, text));
  }
  Widths probe;
  for (int v : axis.values) set_param(probe, axis.name, v);  // throws naming the range
  return axis;
}

CLI::App* add_sweep_command(CLI::App& app, SweepOptions& options) {
  CLI::App* sweep = app.add_subcommand(
      "sweep", "sweep widths and parameters for the designs, in parallel; writes sweep.csv and sweep.json");
  add_common(sweep, options.common);
  sweep->add_option("--file", options.file,
                    "sweep file: one NAME=LO:HI[:STEP] (or NAME=A,B,C, NAME=V) per line, "
                    "'design LIST', '#' comments");
  sweep->add_option("--out", options.out, "output folder")->capture_default_str();
  sweep->add_option("--jobs", options.jobs, "worker threads (default: all cores)");
  return sweep;
}

int run_sweep_command(const SweepOptions& options) {
  std::vector<std::string> settings = options.common.settings;
  std::string design_list = options.common.designs;
  if (!options.file.empty()) {
    std::ifstream in(options.file);
    if (!in) throw std::invalid_argument(fmt::format("{}: cannot open", options.file));
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
      const auto first = line.find_first_not_of(" \t");
      if (first == std::string::npos) continue;
      line = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
      try {
        if (line.rfind("design ", 0) == 0) {
          design_list = line.substr(7);
          parse_design_list(design_list);
        } else {
          parse_axis(line);
          settings.push_back(line);
        }
      } catch (const std::exception& e) {
        throw std::invalid_argument(fmt::format("{}:{}: {}", options.file, number, e.what()));
      }
    }
  }
  std::vector<Config> configs;
  if (settings.empty() && design_list.empty()) {
    configs = default_configs();
  } else {
    std::vector<SweepAxis> axes;
    for (const auto& s : settings) axes.push_back(parse_axis(s));
    configs = product_configs(parse_design_list(design_list), axes);
  }
  for (const Config& c : configs) validate(c.widths);

  const Scene scene = load_scene(options.common.scene, options.common.scene_options);
  std::filesystem::create_directories(options.out);
  const unsigned jobs = options.jobs > 0 ? unsigned(options.jobs)
                                         : std::max(1u, std::thread::hardware_concurrency());
  fmt::print("sweep: {} configurations on {} threads\nscene: {} ({} triangles; {})\nbuild: {}\n"
             "seed: none (deterministic)\n",
             configs.size(), jobs, scene.name, scene.triangles.size(), scene.description, build_id());

  // Snapping depends on subpixel_bits and uv_in_frac: prepare once per pair.
  std::mutex prepared_mutex;
  std::map<std::pair<int, int>, std::shared_ptr<const PreparedScene>> prepared;
  const auto prepared_for = [&](const Widths& w) {
    std::lock_guard<std::mutex> lock(prepared_mutex);
    auto& slot = prepared[{w.subpixel_bits, w.uv_in_frac}];
    if (!slot) slot = std::make_shared<const PreparedScene>(prepare(scene, w));
    return slot;
  };
  prepared_for(configs.front().widths);  // refuse bad input before starting the workers

  std::vector<DesignResult> results(configs.size());
  std::atomic<size_t> next{0}, done{0};
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
          std::lock_guard<std::mutex> lock(failure_mutex);
          if (!failure) failure = std::current_exception();
        }
        ++done;
      }
    });
  while (done < configs.size()) {
    progress(done, configs.size(), elapsed());
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  for (auto& w : workers) w.join();
  progress(done, configs.size(), elapsed());
  if (failure) std::rethrow_exception(failure);

  const std::string csv_path = (std::filesystem::path(options.out) / "sweep.csv").string();
  const std::string json_path = (std::filesystem::path(options.out) / "sweep.json").string();
  std::ofstream csv(csv_path);
  csv << csv_header() << '\n';
  nlohmann::json json;
  json["scene"] = {{"name", scene.name}, {"description", scene.description},
                   {"triangles", scene.triangles.size()}, {"resolution", {scene.width, scene.height}}};
  json["build"] = build_id();
  json["seed"] = nullptr;
  for (const auto& p : param_table()) json["defaults"][p.name] = p.default_value;
  json["rows"] = nlohmann::json::array();
  for (size_t i = 0; i < configs.size(); ++i) {
    csv << csv_row(scene.name, configs[i], results[i]) << '\n';
    nlohmann::json row = results_json(scene, configs[i].widths, {results[i]})["designs"][0];
    row["scene"] = scene.name;
    for (const auto& p : param_table()) row["widths"][p.name] = configs[i].widths.*(p.field);
    for (const auto& [name, value] : configs[i].swept) row["swept"][name] = value;
    json["rows"].push_back(row);
  }
  std::ofstream(json_path) << json.dump(1) << '\n';

  // A readable summary: per design, the range of cycles and the most accurate configuration.
  fmt::print("\n{:<17} {:>7} {:>11} {:>11} {:>10}  {}\n", "design", "configs", "min_cycles",
             "max_cycles", "best_mean", "best configuration");
  for (const Design& d : all_designs()) {
    int64_t lo = -1, hi = -1, count = 0;
    size_t best = configs.size();
    for (size_t i = 0; i < configs.size(); ++i) {
      if (configs[i].design.name != d.name) continue;
      ++count;
      lo = lo < 0 ? results[i].cycles : std::min(lo, results[i].cycles);
      hi = std::max(hi, results[i].cycles);
      if (best == configs.size() || results[i].error.mean < results[best].error.mean) best = i;
    }
    if (count == 0) continue;
    std::string setting;
    for (const auto& [name, value] : configs[best].swept) setting += fmt::format("{}={} ", name, value);
    fmt::print("{:<17} {:>7} {:>11} {:>11} {:>10.3e}  {}\n", d.name, count, lo, hi,
               results[best].error.mean, setting.empty() ? "defaults" : setting);
  }
  fmt::print("\n{} configurations in {:.1f} s; wrote {} and {}\n", configs.size(), elapsed(),
             csv_path, json_path);
  return 0;
}

}  // namespace cdsim
