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
#include <sstream>
#include <stdexcept>
#include <thread>

#include "area.hpp"
#include "cache_files.hpp"
#include "cli_checks.hpp"
#include "common.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "shard.hpp"

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
// that decide its accuracy, around the defaults, or the grid of them
// (model/designs.def: sweep_axes, sweep_grid). 440 configurations; 352
// before cd-linear-div and cd-persp-div, 343 before adaptive, 298 before
// quad-subN, 251 before cd-persp.
std::vector<Config> default_configs() {
  std::vector<Config> configs;
  for (const Design& d : all_designs()) {
    std::vector<SweepAxis> axes;
    for (const std::string& text : d.sweep_axes) axes.push_back(parse_axis(text));
    if (d.sweep_grid) {
      for (const Config& c : product_configs({d}, axes)) configs.push_back(c);
      continue;
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
  h += ",swept,pixels,cycles,pixels_per_clock,table_entries,table_bits,error_mean,"
       "error_rms,error_p99,error_max,footprint_max,texel_mismatch,over_lsb,flagged_triangles";
  // Empty unless the sweep ran with --area and the design has RTL.
  h += ",logic_area_um2,nand2_eq,flops,sram_bits,sram_area_um2,flop_table_area_um2,total_area_um2,"
       "fmax_mhz,mpix_per_s";
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
  row += fmt::format(",{},{},{},{:.6f},{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{}",
                     swept_names(c), r.pixels, r.cycles, r.pixels_per_clock(), r.table_depth,
                     r.table_bits, r.error.mean, r.error.rms, r.error.p99,
                     r.error.max, r.error.footprint_max, r.error.texel_mismatch, r.error.over_lsb,
                     flagged(r));
  if (area) {
    const nlohmann::json a = area_summary_json(*area, r.pixels_per_clock());
    row += fmt::format(",{:.1f},{:.1f},{},{},{:.1f},{:.1f},{:.1f}", area->logic_area_um2,
                       a.at("nand2_eq").get<double>(), a.at("flops").get<int64_t>(), area->sram_bits,
                       area->sram_area_um2, area->flop_table_area_um2, area->total_area_um2);
    // Empty for an estimate: the component model does not time.
    for (const char* key : {"fmax_mhz", "mpix_per_s"})
      row += a.at(key).is_null() ? "," : fmt::format(",{:.2f}", a.at(key).get<double>());
  } else {
    row += ",,,,,,,,,";
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
  CLI::Option* area_flag = sweep->add_flag("--area", options.area,
                  "also synthesise each distinct configuration of a design with RTL (cdsim area: "
                  "Yosys, cached, all cores) and add its area to the rows");
  sweep->add_flag("--area-model", options.area_model,
                  "as --area, but by the component area model (cdsim area --model: an elaboration "
                  "of about 5 s, calibrated by cdsim area-model) instead of full synthesis")
      ->excludes(area_flag);
  add_area_flow_option(sweep, options.area_flow);
  sweep->add_option("--shard", options.shard,
                    "I/N: run only the I-th of N shards (every N-th configuration from the I-th); "
                    "cdsim merge joins the shards' folders into the whole sweep's files");
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
  const Shard shard = options.shard.empty() ? Shard{} : parse_shard("--shard", options.shard);
  const size_t total = configs.size();
  std::vector<size_t> global_index;  // of each configuration this run holds
  {
    std::vector<Config> held;
    for (size_t i = 0; i < configs.size(); ++i)
      if (shard.holds(i)) {
        held.push_back(std::move(configs[i]));
        global_index.push_back(i);
      }
    configs = std::move(held);
  }
  if (!shard.whole()) {
    fmt::print("shard {}/{}: {} of the {} configurations\n", shard.index, shard.count, configs.size(), total);
    std::fflush(stdout);
  }

  // The folder is locked before the long part, so that a second sweep into it stops at once.
  create_output_folder(options.out);
  check_distinct_files({{"--out", std::filesystem::path(options.out) / "sweep.csv"},
                        {"--out", std::filesystem::path(options.out) / "sweep.json"}},
                       {{"--scene", scene_input_file(options.common.scene)}, {"--file", options.file}});
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
  if (!configs.empty()) prepared_for(configs.front().widths);  // refuse bad input before the workers start

  std::vector<DesignResult> results(configs.size());
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  run_parallel(configs.size(), jobs, "sweep", "configurations", [&](size_t i) {
    results[i] = evaluate(*prepared_for(configs[i].widths), configs[i].design, configs[i].widths);
  }, ProgressShown::Always);

  // Area: each distinct configuration synthesised once, after the model runs.
  std::vector<std::optional<AreaReport>> areas(configs.size());
  if (options.area || options.area_model) {
    std::vector<AreaJob> jobs_list;
    std::vector<size_t> rows;
    for (size_t i = 0; i < configs.size(); ++i)
      if (has_rtl(configs[i].design)) {
        jobs_list.push_back({configs[i].design, configs[i].widths});
        rows.push_back(i);
      }
    fmt::print("area: {} configurations with RTL to {} (cached ones are free)\n", jobs_list.size(),
               options.area_model ? "estimate with the component area model" : "synthesise");
    std::fflush(stdout);
    AreaOptions area_options;
    area_options.estimate = options.area_model;
    area_options.flow = options.area_flow;
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
    if (areas[i]) row["area"] = area_summary_json(*areas[i], results[i].pixels_per_clock());
    json["rows"].push_back(row);
  }
  if (!shard.whole())
    json["shard"] = {{"index", shard.index}, {"count", shard.count}, {"configurations", total},
                     {"rows", global_index}};
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

namespace cdsim {

CLI::App* add_merge_command(CLI::App& app, MergeOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "merge", "join shards: the output folders of a sweep --shard I/N into the files the whole "
               "sweep writes, byte for byte; or the regress --shard I/N --json summaries into one "
               "(exit 1 if any shard mismatched)");
  cmd->add_option("shards", options.shards,
                  "the shards' sweep output folders, or their regress --json files; every shard once")
      ->required();
  cmd->add_option("--out", options.out, "output folder (sweeps; created, locked) or JSON file (regressions)")
      ->required();
  return cmd;
}

namespace {

// Regression shards (regress --shard I/N --json FILE): their counts summed.
int merge_regressions(const MergeOptions& options) {
  std::vector<nlohmann::json> parts;
  for (const std::string& file : options.shards) {
    nlohmann::json j = read_json_file(file);
    if (!j.is_object() || j.value("kind", "") != "cdsim regress" || !j.contains("shard"))
      throw std::runtime_error(fmt::format(
          "{}: not the summary of a regression shard (regress --shard I/N --json FILE)", file));
    parts.push_back(std::move(j));
  }
  static const std::vector<std::string> summed = {
      "triangles", "fragments", "mismatches", "hangs", "rtl_cycles", "model_cycles", "clocks", "model_clocks", "setups_compared",
      "table_writes_compared", "y_major_triangles"};
  const auto header = [&](nlohmann::json j) {
    for (const std::string& key : summed) j.erase(key);
    for (const char* key : {"shard", "flags", "failed_triangles"}) j.erase(key);
    return j;
  };
  const uint64_t count = parts.front().at("shard").at("count").get<uint64_t>();
  std::map<uint64_t, std::string> file_of;
  nlohmann::json merged = header(parts.front());
  for (const std::string& key : summed) merged[key] = 0;
  merged["flags"] = nlohmann::json::object();
  std::vector<uint64_t> failed;
  for (size_t i = 0; i < parts.size(); ++i) {
    const nlohmann::json& p = parts[i];
    if (header(p) != header(parts.front()) || p.at("shard").at("count").get<uint64_t>() != count)
      throw std::runtime_error(fmt::format("{} and {} are shards of different regressions (source, seed, widths, "
                                           "design, back-pressure, build or shard count differ)",
                                           options.shards.front(), options.shards[i]));
    const uint64_t index = p.at("shard").at("index").get<uint64_t>();
    const auto [it, added] = file_of.emplace(index, options.shards[i]);
    if (!added)
      throw std::runtime_error(fmt::format("{} and {} are both shard {}/{}", it->second, options.shards[i], index,
                                           count));
    for (const std::string& key : summed) merged[key] = merged[key].get<int64_t>() + p.at(key).get<int64_t>();
    for (const auto& [flag, n] : p.at("flags").items())
      merged["flags"][flag] = merged["flags"].value(flag, int64_t{0}) + n.get<int64_t>();
    for (const auto& f : p.at("failed_triangles")) failed.push_back(f.get<uint64_t>());
  }
  std::string missing;
  for (uint64_t i = 1; i <= count; ++i)
    if (!file_of.count(i)) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", i, count);
  if (!missing.empty()) throw std::runtime_error(fmt::format("shard {} missing: give every shard once", missing));
  std::sort(failed.begin(), failed.end());
  merged["failed_triangles"] = failed;
  merged["shards"] = count;
  check_output_folder("--out", options.out);
  std::vector<NamedFile> inputs;
  for (const std::string& file : options.shards) inputs.push_back({"shard", file});
  check_distinct_files({{"--out", options.out}}, inputs);
  write_file_atomic(options.out, merged.dump(2) + "\n");
  const int64_t bad = merged["mismatches"].get<int64_t>() + merged["hangs"].get<int64_t>();
  fmt::print("merged {} regression shards: {} triangles, {} fragments compared, {} mismatches, {} hangs, RTL "
             "cycles {}, model cycles {}; wrote {}\n",
             count, merged["triangles"].get<int64_t>(), merged["fragments"].get<int64_t>(),
             merged["mismatches"].get<int64_t>(), merged["hangs"].get<int64_t>(),
             merged["rtl_cycles"].get<int64_t>(), merged["model_cycles"].get<int64_t>(), options.out);
  return bad == 0 ? 0 : 1;
}

}  // namespace

int run_merge_command(const MergeOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ignored;
  if (fs::is_regular_file(options.shards.front(), ignored)) return merge_regressions(options);
  struct Part {
    std::string folder;
    nlohmann::json json;
    std::vector<std::string> rows;  // CSV lines after the header
    std::string header;
  };
  std::vector<Part> parts;
  for (const std::string& folder : options.shards) {
    Part p;
    p.folder = folder;
    const fs::path json_path = fs::path(folder) / "sweep.json", csv_path = fs::path(folder) / "sweep.csv";
    p.json = read_json_file(json_path);
    if (!p.json.is_object() || !p.json.contains("shard") || !p.json.contains("rows"))
      throw std::runtime_error(fmt::format("{}: not a shard of a sweep (no 'shard'): was it run with --shard I/N?",
                                           json_path.string()));
    std::istringstream csv(read_text_file(csv_path));
    std::getline(csv, p.header);
    for (std::string line; std::getline(csv, line);) p.rows.push_back(line);
    const auto& shard = p.json.at("shard");
    if (p.rows.size() != p.json.at("rows").size() || p.rows.size() != shard.at("rows").size())
      throw std::runtime_error(fmt::format("{}: sweep.csv has {} rows but sweep.json {}", folder, p.rows.size(),
                                           p.json.at("rows").size()));
    parts.push_back(std::move(p));
  }
  const auto whole_header = [](nlohmann::json j) {
    j.erase("shard");
    j.erase("rows");
    return j;
  };
  const Part& first = parts.front();
  const uint64_t count = first.json.at("shard").at("count").get<uint64_t>();
  const uint64_t total = first.json.at("shard").at("configurations").get<uint64_t>();
  std::map<uint64_t, std::string> folder_of;
  for (const Part& p : parts) {
    const auto& s = p.json.at("shard");
    if (s.at("count").get<uint64_t>() != count || s.at("configurations").get<uint64_t>() != total ||
        whole_header(p.json) != whole_header(first.json) || p.header != first.header)
      throw std::runtime_error(fmt::format(
          "{} and {} are shards of different sweeps (shard count, configurations, scene, build or columns "
          "differ)", first.folder, p.folder));
    const uint64_t index = s.at("index").get<uint64_t>();
    const auto [it, added] = folder_of.emplace(index, p.folder);
    if (!added)
      throw std::runtime_error(fmt::format("{} and {} are both shard {}/{}", it->second, p.folder, index, count));
  }
  std::string missing;
  for (uint64_t i = 1; i <= count; ++i)
    if (!folder_of.count(i)) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", i, count);
  if (!missing.empty()) throw std::runtime_error(fmt::format("shard {} missing: give every shard once", missing));

  std::vector<const nlohmann::json*> json_rows(total, nullptr);
  std::vector<const std::string*> csv_rows(total, nullptr);
  for (const Part& p : parts) {
    const auto& s = p.json.at("shard");
    const uint64_t index = s.at("index").get<uint64_t>();
    for (size_t k = 0; k < p.rows.size(); ++k) {
      const uint64_t g = s.at("rows").at(k).get<uint64_t>();
      if (g >= total || g % count != index - 1 || json_rows[g])
        throw std::runtime_error(fmt::format("{}/sweep.json: row {} names configuration {}, which is not shard "
                                             "{}/{}'s or is given twice", p.folder, k, g, index, count));
      json_rows[g] = &p.json.at("rows").at(k);
      csv_rows[g] = &p.rows[k];
    }
  }
  nlohmann::json merged = whole_header(first.json);
  merged["rows"] = nlohmann::json::array();
  std::string csv = first.header + '\n';
  for (uint64_t g = 0; g < total; ++g) {
    if (!json_rows[g])
      throw std::runtime_error(fmt::format("configuration {} of {} is in no shard", g, total));
    merged["rows"].push_back(*json_rows[g]);
    csv += *csv_rows[g] + '\n';
  }
  create_output_folder(options.out);
  std::vector<NamedFile> inputs;
  for (const std::string& folder : options.shards)
    for (const char* name : {"sweep.csv", "sweep.json"}) inputs.push_back({"shard", fs::path(folder) / name});
  check_distinct_files({{"--out", fs::path(options.out) / "sweep.csv"}, {"--out", fs::path(options.out) / "sweep.json"}},
                       inputs);
  const OutputFolderLock lock(options.out);
  const std::string csv_path = (fs::path(options.out) / "sweep.csv").string();
  const std::string json_path = (fs::path(options.out) / "sweep.json").string();
  write_files_atomic({{json_path, merged.dump(1) + '\n'}, {csv_path, csv}});
  fmt::print("merged {} shards: {} configurations; wrote {} and {}\n", count, total, csv_path, json_path);
  return 0;
}

}  // namespace cdsim
