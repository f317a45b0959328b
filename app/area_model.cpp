#include "area_model.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <mutex>
#include <random>
#include <set>

#include "area_detail.hpp"
#include "build_info.hpp"
#include "cache_files.hpp"
#include "cli_checks.hpp"
#include "column_walker.hpp"
#include "common.hpp"
#include "progress.hpp"
#include "rtl_sources.hpp"

namespace cdsim {

namespace fs = std::filesystem;
using namespace area_detail;

namespace {

// Bumped whenever the elaboration below or the features change.
constexpr const char* kCoarseFlow = "coarse-flow-2";
constexpr size_t kFeatureCount = kAreaFeatures.size();

enum Feature : size_t {
  kMul, kAdd, kCompare, kEqual, kMux, kPmux, kFlop, kAsyncFlop, kShift, kLogic, kReduce, kOther,
  kConstAdd, kRom
};

// Bits of a connection that are not constants (Yosys JSON: net numbers, or
// "0" / "1" / "x" / "z" for constant bits).
double live_bits(const nlohmann::json& cell, const char* port) {
  const auto& connections = cell.at("connections");
  if (!connections.contains(port)) return 0;
  double bits = 0;
  for (const auto& bit : connections.at(port))
    if (bit.is_number()) ++bits;
  return bits;
}

double port_width(const nlohmann::json& cell, const char* port) {
  const auto& connections = cell.at("connections");
  return connections.contains(port) ? static_cast<double>(connections.at(port).size()) : 0;
}

}  // namespace

void add_cell_features(const std::string& type, const nlohmann::json& cell, AreaFeatures& f) {
  const auto is = [&](std::initializer_list<const char*> types) {
    return std::any_of(types.begin(), types.end(), [&](const char* t) { return type == t; });
  };
  if (type == "$mul") {
    // Partial-product bits that reach the kept part of the product.
    const int a = static_cast<int>(live_bits(cell, "A")), b = static_cast<int>(live_bits(cell, "B"));
    const int y = static_cast<int>(port_width(cell, "Y"));
    double bits = 0;
    for (int i = 0; i < a; ++i) bits += std::max(0, std::min(b, y - i));
    f[kMul] += bits;
  } else if (is({"$add", "$sub", "$alu"}) && (live_bits(cell, "A") == 0 || live_bits(cell, "B") == 0)) {
    // A constant operand (i + 1, the Kim chain's unit steps): half adders.
    f[kConstAdd] += port_width(cell, "Y");
  } else if (is({"$add", "$sub", "$neg", "$alu"})) {
    f[kAdd] += port_width(cell, "Y");
  } else if (is({"$lt", "$le", "$gt", "$ge"})) {
    f[kCompare] += std::max(live_bits(cell, "A"), live_bits(cell, "B"));
  } else if (is({"$eq", "$ne", "$eqx", "$nex"})) {
    f[kEqual] += std::max(live_bits(cell, "A"), live_bits(cell, "B"));
  } else if (type == "$mux") {
    f[kMux] += port_width(cell, "Y");
  } else if (type == "$pmux") {
    f[kPmux] += port_width(cell, "Y") * port_width(cell, "S");
  } else if (is({"$adff", "$adffe", "$dffsr", "$dffsre", "$aldff", "$aldffe"})) {
    f[kAsyncFlop] += port_width(cell, "Q");
  } else if (type.find("dff") != std::string::npos) {
    f[kFlop] += port_width(cell, "Q");
  } else if (is({"$shift", "$shiftx"}) && live_bits(cell, "A") == 0) {
    // A part-select of a constant vector is a ROM (cd-persp's 1/m table):
    // its logic grows with the table's bits, not with the index's.
    f[kRom] += port_width(cell, "A");
  } else if (is({"$shl", "$shr", "$sshl", "$sshr", "$shift", "$shiftx"})) {
    f[kShift] += port_width(cell, "Y") * std::max(1.0, live_bits(cell, "B"));
  } else if (is({"$and", "$or", "$xor", "$xnor", "$not"})) {
    f[kLogic] += port_width(cell, "Y");
  } else if (type.rfind("$reduce_", 0) == 0 || type.rfind("$logic_", 0) == 0) {
    f[kReduce] += std::max(live_bits(cell, "A"), live_bits(cell, "B"));
  } else {
    f[kOther] += port_width(cell, "Y");
  }
}

namespace {

// A module of the elaborated (unmapped) netlist.
struct CoarseModule {
  std::string kind;  // base name: setup_engine, shift_round, cd_scan_unit, ...
  AreaFeatures features{};
  int64_t flops = 0;
  std::map<std::string, int64_t> submodules;
};
using Inventory = std::map<std::string, CoarseModule>;

Inventory inventory_from_yosys_json(const nlohmann::json& netlist) {
  Inventory out;
  const auto& modules = netlist.at("modules");
  const auto black_box = [&](const std::string& name) {
    const auto& m = modules.at(name);
    return m.contains("attributes") && m.at("attributes").contains("blackbox");
  };
  for (const auto& [name, module] : modules.items()) {
    if (black_box(name)) continue;
    CoarseModule m;
    m.kind = base_name(name);
    for (const auto& [cell_name, cell] : module.at("cells").items()) {
      const std::string type = cell.at("type").get<std::string>();
      if (modules.contains(type)) {
        if (!black_box(type)) ++m.submodules[type];  // the SRAM table is not logic
      } else if (type.rfind("$paramod", 0) == 0 || type[0] != '$') {
        continue;  // a black box (the SRAM table)
      } else {
        add_cell_features(type, cell, m.features);
        if (type.find("dff") != std::string::npos)
          m.flops += static_cast<int64_t>(port_width(cell, "Q"));
      }
    }
    out[name] = m;
  }
  return out;
}

nlohmann::json inventory_json(const Inventory& inv) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, m] : inv)
    out[name] = {{"kind", m.kind}, {"features", m.features}, {"flops", m.flops}, {"submodules", m.submodules}};
  return out;
}

Inventory inventory_of(const nlohmann::json& j) {
  Inventory out;
  for (const auto& [name, m] : j.items()) {
    CoarseModule c;
    c.kind = m.at("kind").get<std::string>();
    c.features = m.at("features").get<AreaFeatures>();
    c.flops = m.at("flops").get<int64_t>();
    c.submodules = m.at("submodules").get<std::map<std::string, int64_t>>();
    out[name] = c;
  }
  return out;
}

struct CoarseResult {
  Inventory unit, table;  // table empty without one
  double seconds = 0;
};

// The elaborated netlist of the unit (and flip-flop table), cached in the
// configuration's folder beside the full synthesis.
CoarseResult coarse_pass(const UnitConfig& config) {
  const EntryLock lock(config, fmt::format("area: the elaboration in {}", config.dir.string()));
  CoarseResult r;
  const auto check = [&](const nlohmann::json& j) -> std::string {
    if (!j.is_object() || j.value("flow", "") != kCoarseFlow) return fmt::format("not of flow {}", kCoarseFlow);
    const double seconds = j.at("seconds").get<double>();
    if (!std::isfinite(seconds) || seconds < 0) return fmt::format("'seconds' is {}", seconds);
    r = {inventory_of(j.at("unit")), inventory_of(j.at("table")), seconds};
    for (const Inventory* inv : {&r.unit, &r.table})
      for (const auto& [name, m] : *inv) {
        if (m.flops < 0) return fmt::format("module {}: {} flip-flops", name, m.flops);
        for (const double f : m.features)
          if (!std::isfinite(f) || f < 0) return fmt::format("module {}: a feature is {}", name, f);
      }
    return "";
  };
  if (cached_result(config, "inventory.json", check)) return r;
  build_result(config, "inventory.json", [&](const fs::path& work) {
    static const char* kElaborate = "proc\nopt -fast\nwreduce\nopt -fast\n";
    const auto start = std::chrono::steady_clock::now();
    const auto run = [&](const std::string& what, const std::string& script) {
      const fs::path json = work / ("coarse_" + what + ".json");
      write_file_atomic(work / ("coarse_" + what + ".ys"), script + fmt::format("write_json {}\n", json.string()));
      run_yosys({{work / ("coarse_" + what + ".ys"), work / ("coarse_" + what + ".log"), "elaborating the " + what}});
      Inventory inv = inventory_from_yosys_json(read_json_file(json));
      fs::remove(json);  // megabytes; the inventory keeps what the model needs
      return inv;
    };
    r = {};
    r.unit = run("unit", config.unit_front(work) + kElaborate + "memory -nomap\nopt_clean\n");
    if (config.has_table) r.table = run("table", config.table_front(work) + kElaborate + "memory\nopt -fast\nopt_clean\n");
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_file_atomic(work / "inventory.json", nlohmann::json{{"flow", kCoarseFlow},
                                                              {"seconds", r.seconds},
                                                              {"unit", inventory_json(r.unit)},
                                                              {"table", inventory_json(r.table)}}
                                                   .dump() + "\n");
  });
  return r;
}

// A kind's own coefficients, else those fitted to every kind.
std::map<std::string, AreaFeatures>::const_iterator coefficients_for(
    const std::map<std::string, AreaFeatures>& coefficients, const std::string& kind) {
  const auto it = coefficients.find(kind);
  if (it != coefficients.end()) return it;
  // The setup engine's products moved into their own module (setup_multipliers)
  // after the committed model's calibration, where they were the setup engine's
  // own cells: until a calibration that has them, they take its coefficients.
  if (kind == "setup_multipliers" && coefficients.count("setup_engine")) return coefficients.find("setup_engine");
  return coefficients.find(kAnyKind);
}

double dot(const AreaFeatures& a, const AreaFeatures& b) {
  double s = 0;
  for (size_t i = 0; i < kFeatureCount; ++i) s += a[i] * b[i];
  return s;
}

// The predicted statistics of an inventory, as parse_stat gives a synthesis's.
std::map<std::string, ModuleStat> predicted_stat(const Inventory& inv, const AreaModel& model,
                                                 const std::string& what) {
  std::map<std::string, ModuleStat> out;
  for (const auto& [name, m] : inv) {
    const auto it = coefficients_for(model.coefficients, m.kind);
    if (it == model.coefficients.end())
      throw std::runtime_error(fmt::format(
          "the area model has no coefficients for module '{}' of the {}: calibrate it with "
          "cdsim area-model",
          m.kind, what));
    ModuleStat s;
    s.own_area = dot(m.features, it->second);
    s.own_flops = m.flops;
    s.submodules = m.submodules;
    out[name] = s;
  }
  return out;
}

std::string liberty_name(const std::string& liberty) { return fs::path(liberty).filename().string(); }

}  // namespace

std::string default_area_model_path() { return (fs::path(kRtlDir) / "area_model.json").string(); }

std::string rtl_sources_hash(const std::string& flow) {
  uint64_t hash = fnv1a(flow.empty() ? std::string(kCoarseFlow) : flow);
  for (const fs::path& source : rtl_sources_of(kScanUnitTop)) hash = fnv1a(read_text_file(source), hash);
  return fmt::format("{:016x}", hash);
}

std::string default_area_archive_path() { return (fs::path(kRtlDir) / "area_calibration.json").string(); }

nlohmann::json load_area_archive(const std::string& path) {
  if (!fs::exists(path)) return nlohmann::json::object();
  try {
    const nlohmann::json j = read_json_file(path);
    const std::string flow = j.at("flow").get<std::string>();
    const nlohmann::json& configs = j.at("configurations");
    if (!configs.is_object()) throw std::runtime_error("'configurations' is not an object");
    if (flow == kCoarseFlow) return configs;
    // Another elaboration flow: the syntheses stand if the sources are those
    // they were made of; the inventories are elaborated again.
    const std::string old_sources = rtl_sources_hash(flow), sources = rtl_sources_hash();
    nlohmann::json kept = nlohmann::json::object();
    for (const auto& [key, entry] : configs.items()) {
      if (entry.value("rtl_hash", "") != old_sources) continue;
      nlohmann::json e = entry;
      e.erase("inventory");
      e["rtl_hash"] = sources;
      kept[key] = e;
    }
    std::cerr << fmt::format("area-model: {} is for elaboration flow {}, this build uses {}: {} of {} "
                             "syntheses kept (the RTL unchanged), to be elaborated again\n",
                             path, flow, kCoarseFlow, kept.size(), configs.size());
    return kept;
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: not a usable calibration archive: {}", path, e.what()));
  }
}

AreaModel load_area_model(const std::string& path) {
  if (!fs::exists(path))
    throw std::runtime_error(fmt::format("{}: no area model; make one with cdsim area-model", path));
  nlohmann::json j;
  try {
    j = read_json_file(path);
    AreaModel m;
    if (j.at("flow").get<std::string>() != kCoarseFlow)
      throw std::runtime_error(fmt::format("it is for flow {}, this build uses {}",
                                           j.at("flow").get<std::string>(), kCoarseFlow));
    for (const auto& [kind, c] : j.at("coefficients").items()) m.coefficients[kind] = c.get<AreaFeatures>();
    m.liberty = j.at("liberty").get<std::string>();
    m.rtl_hash = j.at("rtl_hash").get<std::string>();
    m.calibration = j.value("calibration", nlohmann::json::object());
    return m;
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{}: not a usable area model: {}", path, e.what()));
  }
}

AreaReport estimate_area(const Design& design, const Widths& widths, const AreaOptions& options) {
  static std::mutex mutex;
  static std::map<std::string, AreaModel> models;
  const std::string path = options.model_path.empty() ? default_area_model_path() : options.model_path;
  // Loaded once per path and never changed or erased: a std::map keeps the
  // entry where it is, so every thread reads it without a copy.
  const AreaModel* model = nullptr;
  {
    std::lock_guard<std::mutex> guard(mutex);
    if (!models.count(path)) {
      AreaModel loaded = load_area_model(path);
      if (loaded.rtl_hash != rtl_sources_hash())
        std::cerr << fmt::format(
            "area: warning: {} was calibrated on other RTL sources; re-run cdsim area-model\n", path);
      models.emplace(path, std::move(loaded));
    }
    model = &models.at(path);
  }
  if (model->liberty != liberty_name(options.liberty))  // on every call: the library can differ
    throw std::runtime_error(
        fmt::format("{}: calibrated on {}, not {}", path, model->liberty, liberty_name(options.liberty)));
  const UnitConfig config = prepare_unit(design, widths, options);
  const CoarseResult coarse = coarse_pass(config);
  const auto unit = predicted_stat(coarse.unit, *model, "unit");
  const nlohmann::json estimated = {
      {"seconds", coarse.seconds},
      {"blocks", block_areas(unit, config, path, {})},
      {"flop_table_lines", config.flop_lines},
      {"flop_table_area_um2",
       config.has_table ? table_area(predicted_stat(coarse.table, *model, "flip-flop table")) : 0.0}};
  AreaReport report = area_report(design, widths, config, estimated, options);
  report.estimated = true;
  for (BlockArea& b : report.blocks) b.mul_a_bits = b.mul_b_bits = b.mul_product_bits = -1;  // not sized here
  report.log_path = path;
  return report;
}

Widths random_widths(uint64_t seed, const std::string& tag, int index) {
  std::mt19937_64 rng(fnv1a(fmt::format("{} {} {}", seed, tag, index)));
  // Plain modulo rather than std::uniform_int_distribution, whose output the
  // standard leaves to the library: the same seed gives the same widths anywhere.
  const auto draw = [&](int lo, int hi) {
    return lo + static_cast<int>(rng() % static_cast<uint64_t>(hi - lo + 1));
  };
  for (int attempt = 0; attempt < 10000; ++attempt) {
    Widths w;
    for (const ParamInfo& p : param_table())
      w.*(p.field) = p.field == &Widths::table_depth ? 4 << draw(0, 10) : draw(p.min_value, p.max_value);
    // The draws the committed calibration (rtl/area_calibration.json) was
    // made of: validate() then also kept the walker's accumulator within 64
    // bits; it allows more since, but the same seed must give the same
    // configurations, or the archive's syntheses would be redone.
    if (!walker_fits_64(w)) continue;
    try {
      validate(w);
      return w;
    } catch (const std::invalid_argument&) {
    }
  }
  throw std::logic_error("random_widths: no valid widths in 10000 draws");
}

namespace {

// min |A x - y| subject to x >= 0, by Lawson and Hanson's active-set method
// (Solving Least Squares Problems, 1974, ch. 23): features join the passive
// set while the residual's gradient favours one of them, and leave it when
// the unconstrained fit on the passive set would make them negative. Columns
// are scaled to unit length first (the features span 1 to 10^5), and the fit
// on a passive set is the smallest-norm one (collinear features).
Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& a_raw, const Eigen::VectorXd& y) {
  const Eigen::Index n = a_raw.cols();
  Eigen::VectorXd scale = a_raw.colwise().norm().transpose();
  Eigen::MatrixXd a = a_raw;
  for (Eigen::Index j = 0; j < n; ++j)
    if (scale(j) > 0) a.col(j) /= scale(j);
  const double tolerance = 1e-12 * std::max(1.0, y.norm()) * static_cast<double>(std::max<Eigen::Index>(n, 1));
  std::vector<bool> passive(static_cast<size_t>(n), false);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  // The fit on the passive set, zero elsewhere.
  const auto passive_fit = [&] {
    std::vector<Eigen::Index> cols;
    for (Eigen::Index j = 0; j < n; ++j)
      if (passive[static_cast<size_t>(j)]) cols.push_back(j);
    Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(cols.size()));
    for (size_t k = 0; k < cols.size(); ++k) sub.col(static_cast<Eigen::Index>(k)) = a.col(cols[k]);
    const Eigen::VectorXd z = sub.completeOrthogonalDecomposition().solve(y);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
    for (size_t k = 0; k < cols.size(); ++k) s(cols[k]) = z(static_cast<Eigen::Index>(k));
    return s;
  };
  for (Eigen::Index iteration = 0; iteration < 30 * std::max<Eigen::Index>(n, 1); ++iteration) {
    const Eigen::VectorXd gradient = a.transpose() * (y - a * x);
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!passive[static_cast<size_t>(j)] && scale(j) > 0 && gradient(j) > tolerance &&
          (best < 0 || gradient(j) > gradient(best)))
        best = j;
    if (best < 0) break;  // optimal: no free feature would lower the residual
    passive[static_cast<size_t>(best)] = true;
    Eigen::VectorXd s = passive_fit();
    for (Eigen::Index inner = 0; inner <= n; ++inner) {
      double alpha = 1;  // the step towards s that keeps x >= 0
      bool infeasible = false;
      for (Eigen::Index j = 0; j < n; ++j)
        if (passive[static_cast<size_t>(j)] && s(j) <= 0) {
          infeasible = true;
          const double gap = x(j) - s(j);  // 0 only if x(j) = s(j) = 0: no step
          alpha = std::min(alpha, gap > 0 ? x(j) / gap : 0.0);
        }
      if (!infeasible) break;
      x += alpha * (s - x);
      for (Eigen::Index j = 0; j < n; ++j)
        if (passive[static_cast<size_t>(j)] && x(j) <= 0) {
          passive[static_cast<size_t>(j)] = false;
          x(j) = 0;
        }
      s = passive_fit();
    }
    x = s;
  }
  for (Eigen::Index j = 0; j < n; ++j) x(j) = scale(j) > 0 ? std::max(0.0, x(j)) / scale(j) : 0;
  return x;
}

}  // namespace

std::map<std::string, AreaFeatures> fit_area_coefficients(const std::vector<AreaSample>& samples,
                                                          size_t leave_out) {
  std::map<std::string, std::vector<const AreaSample*>> by_kind;
  for (const AreaSample& s : samples)
    if (s.config != leave_out) {
      by_kind[s.kind].push_back(&s);
      by_kind[kAnyKind].push_back(&s);
    }
  std::map<std::string, AreaFeatures> out;
  for (const auto& [kind, list] : by_kind) {
    Eigen::MatrixXd x(static_cast<Eigen::Index>(list.size()), static_cast<Eigen::Index>(kFeatureCount));
    Eigen::VectorXd y(static_cast<Eigen::Index>(list.size()));
    for (size_t r = 0; r < list.size(); ++r) {
      for (size_t c = 0; c < kFeatureCount; ++c)
        x(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = list[r]->features[c];
      y(static_cast<Eigen::Index>(r)) = list[r]->area;
    }
    // A kind with too few samples for its own fit takes the fit of every kind.
    const auto used = static_cast<size_t>((x.array() != 0).colwise().any().count());
    if (kind != kAnyKind && list.size() < kSamplesPerFeature * std::max<size_t>(used, 1)) continue;
    const Eigen::VectorXd beta = nonnegative_least_squares(x, y);
    AreaFeatures c{};
    for (size_t i = 0; i < kFeatureCount; ++i) c[i] = beta(static_cast<Eigen::Index>(i));
    out[kind] = c;
  }
  return out;
}

namespace {

// Sum of own areas over the hierarchy below `name`.
double predicted_total(const Inventory& inv, const std::string& name,
                       const std::map<std::string, AreaFeatures>& coefficients, bool& missing) {
  const CoarseModule& m = inv.at(name);
  const auto it = coefficients_for(coefficients, m.kind);
  double area = 0;
  if (it == coefficients.end()) missing = true;
  else area = dot(m.features, it->second);
  for (const auto& [sub, count] : m.submodules)
    area += static_cast<double>(count) * predicted_total(inv, sub, coefficients, missing);
  return area;
}

struct CalibrationConfig {
  Design design;
  Widths widths;
  CoarseResult coarse;
  double logic = 0, table = 0;  // synthesised
};

std::string top_of(const Inventory& inv, const std::string& base) {
  for (const auto& [name, m] : inv)
    if (m.kind == base) return name;
  throw std::runtime_error("area model: the elaborated netlist has no module " + base);
}

}  // namespace

CLI::App* add_area_model_command(CLI::App& app, AreaModelOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "area-model",
      "calibrate the component area model on full syntheses of random configurations and "
      "measure its error (each configuration left out of the fit in turn)");
  cmd->add_option("--configs", options.configs, "random configurations per design")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--seed", options.seed, "seed of the random configurations")->capture_default_str();
  cmd->add_option("--design", options.designs, "comma-separated designs, or all")->capture_default_str();
  cmd->add_option("--jobs", options.jobs, "Yosys runs at a time (default: all cores)")
      ->check(CLI::Range(1u, 256u));
  cmd->add_option("--write", options.write_path, "write the model here (default: rtl/area_model.json)");
  cmd->add_option("--json", options.json_path, "also write the per-configuration errors as JSON");
  cmd->add_option("--archive", options.archive_path,
                  "syntheses and elaborations of earlier calibrations, reused and extended "
                  "(default: rtl/area_calibration.json)");
  cmd->add_flag("--no-archive", options.no_archive, "neither read nor write an archive")
      ->excludes("--archive");
  cmd->add_flag("--archive-only", options.archive_only,
                "fail rather than synthesise a configuration the archive lacks")
      ->excludes("--no-archive");
  cmd->add_option("--cache", options.area.cache_dir, "cache folder (as cdsim area --cache)");
  cmd->add_option("--liberty", options.area.liberty, "standard-cell liberty file")->capture_default_str();
  return cmd;
}

int run_area_model_command(const AreaModelOptions& options) {
  const std::vector<Design> designs = [&] {
    std::vector<Design> out;
    for (const Design& d : designs_from(options.designs))
      // Calibrated on the scan unit's designs; the adaptive unit is synthesised.
      if (has_rtl(d) && rtl_top(d) == RtlTop::ScanUnit) out.push_back(d);
    return out;
  }();
  const std::string write_path = options.write_path.empty() ? default_area_model_path() : options.write_path;
  check_output_folder("--write", write_path);
  if (!options.json_path.empty()) check_output_folder("--json", options.json_path);
  // The archive is read and rewritten: an output of its own, not an input.
  check_distinct_files({{"--write", write_path},
                        {"--json", options.json_path},
                        {"--archive", options.no_archive ? std::string()
                                      : options.archive_path.empty() ? default_area_archive_path()
                                                                     : options.archive_path}},
                       {{"--liberty", options.area.liberty}});
  std::vector<CalibrationConfig> configs;
  // Round robin over the designs, so that an interrupted calibration has them all.
  for (int i = 0; i < options.configs; ++i)
    for (const Design& d : designs) configs.push_back({d, random_widths(options.seed, d.name, i), {}, 0, 0});
  fmt::print("area-model: {} designs x {} random configurations (seed {}), build {}\n", designs.size(),
             options.configs, options.seed, kBuildRevision);
  std::fflush(stdout);

  // What an earlier calibration recorded (the archive) is reused: its key is
  // the configuration's cache key, which covers the RTL, widths, design and flow.
  AreaOptions area = options.area;
  area.estimate = false;
  area.quiet = true;
  const std::string archive_path =
      options.archive_path.empty() ? default_area_archive_path() : options.archive_path;
  if (!options.no_archive) check_output_folder("--archive", archive_path);
  const nlohmann::json archive = options.no_archive ? nlohmann::json::object() : load_area_archive(archive_path);
  std::vector<std::string> keys(configs.size());
  std::vector<size_t> pending;
  // Synthesised (from the archive); pending then means elaborated only.
  std::vector<char> synthesised(configs.size(), 0);
  std::vector<std::map<std::string, double>> unit_own(configs.size()), table_own(configs.size());
  for (size_t i = 0; i < configs.size(); ++i) {
    keys[i] = prepare_unit(configs[i].design, configs[i].widths, area).dir.filename().string();
    if (archive.contains(keys[i])) {
      const nlohmann::json& a = archive.at(keys[i]);
      configs[i].logic = a.at("logic_area_um2").get<double>();
      configs[i].table = a.at("flop_table_area_um2").get<double>();
      unit_own[i] = a.at("own_area").at("unit").get<std::map<std::string, double>>();
      table_own[i] = a.at("own_area").at("table").get<std::map<std::string, double>>();
      synthesised[i] = 1;
      if (a.contains("inventory")) {
        configs[i].coarse.unit = inventory_of(a.at("inventory").at("unit"));
        configs[i].coarse.table = inventory_of(a.at("inventory").at("table"));
        continue;
      }
    }
    pending.push_back(i);
  }
  const size_t to_elaborate =
      static_cast<size_t>(std::count_if(pending.begin(), pending.end(), [&](size_t i) { return synthesised[i]; }));
  fmt::print("{} of {} configurations from {}{}{}\n", configs.size() - pending.size(), configs.size(),
             options.no_archive ? "an archive (none given)" : archive_path,
             to_elaborate ? fmt::format("; {} synthesised there, to be elaborated again", to_elaborate) : "",
             pending.size() > to_elaborate ? "; the others are synthesised and elaborated" : "");
  std::fflush(stdout);
  if (!pending.empty() && options.archive_only) {
    std::string missing;
    for (size_t k = 0; k < std::min<size_t>(pending.size(), 5); ++k)
      missing += fmt::format("\n  {} {}", configs[pending[k]].design.name, describe(configs[pending[k]].widths));
    throw std::runtime_error(fmt::format("area-model --archive-only: {} of {} configurations are not in {} "
                                         "or lack this flow's elaboration, for example:{}",
                                         pending.size(), configs.size(), archive_path, missing));
  }

  // Each pending configuration is synthesised (cached), then elaborated for
  // the model, and recorded in the archive as soon as it is done: a
  // calibration of hours that is stopped keeps what it finished.
  const std::string rtl = rtl_sources_hash();
  nlohmann::json updated = nlohmann::json::object();
  for (const auto& [key, a] : archive.items())
    if (a.value("rtl_hash", "") == rtl) updated[key] = a;
  const auto own_areas = [](const std::map<std::string, ModuleStat>& stat) {
    std::map<std::string, double> out;
    for (const auto& [name, m] : stat) out[name] = m.own_area;
    return out;
  };
  std::mutex archive_mutex;
  const char* progress_label = to_elaborate == pending.size()
                                   ? "configurations (Yosys elaboration; syntheses archived)"
                                   : "configurations (Yosys synthesis + elaboration, cached)";
  run_parallel(pending.size(), options.jobs, "area-model", progress_label,
               [&](size_t k) {
                 const size_t i = pending[k];
                 CalibrationConfig& c = configs[i];
                 if (!synthesised[i]) c.logic = synthesise_area(c.design, c.widths, area).logic_area_um2;
                 const UnitConfig u = prepare_unit(c.design, c.widths, area);
                 c.coarse = coarse_pass(u);
                 if (!synthesised[i]) {
                   unit_own[i] = own_areas(parse_stat(read_text_file(u.dir / "unit.log")));
                   if (u.has_table) {
                     const auto table = parse_stat(read_text_file(u.dir / "table.log"));
                     c.table = table_area(table);
                     table_own[i] = own_areas(table);
                   }
                 }
                 if (options.no_archive) return;
                 const nlohmann::json entry = {
                     {"design", c.design.name},
                     {"widths", describe(c.widths)},
                     {"rtl_hash", rtl},
                     {"logic_area_um2", c.logic},
                     {"flop_table_area_um2", c.table},
                     {"own_area", {{"unit", unit_own[i]}, {"table", table_own[i]}}},
                     {"inventory",
                      {{"unit", inventory_json(c.coarse.unit)}, {"table", inventory_json(c.coarse.table)}}}};
                 std::lock_guard<std::mutex> guard(archive_mutex);
                 updated[keys[i]] = entry;
                 write_file_atomic(archive_path,
                                   nlohmann::json{{"flow", kCoarseFlow}, {"configurations", updated}}.dump() + "\n");
               });
  if (!options.no_archive && !pending.empty())
    fmt::print("wrote {} ({} configurations)\n", archive_path, updated.size());

  // Samples: every distinct module with its synthesised own area.
  std::vector<AreaSample> samples;
  std::set<std::string> sampled;
  const auto collect = [&](size_t i, const Inventory& inv, const std::map<std::string, double>& own,
                           const std::string& what) {
    for (const auto& [name, m] : inv) {
      const auto it = own.find(name);
      if (it == own.end())
        throw std::runtime_error(fmt::format("area model: module {} of the {} elaborated but not in the "
                                             "synthesis statistics",
                                             name, what));
      // One sample per module and configuration: a module's name encodes its
      // parameters but not the widths it reads from cd_widths.svh.
      if (sampled.insert(fmt::format("{} #{}", name, i)).second)
        samples.push_back({m.kind, m.features, it->second, i});
    }
  };
  for (size_t i = 0; i < configs.size(); ++i) {
    collect(i, configs[i].coarse.unit, unit_own[i], "unit");
    if (!configs[i].coarse.table.empty()) collect(i, configs[i].coarse.table, table_own[i], "flip-flop table");
  }

  // Each configuration predicted by a fit that has seen none of its modules.
  struct Row {
    double unit_error = 0, table_error = 0;
    bool has_table = false, missing = false;
  };
  std::vector<Row> rows(configs.size());
  for (size_t i = 0; i < configs.size(); ++i) {
    const auto coefficients = fit_area_coefficients(samples, i);
    Row& r = rows[i];
    const double unit = predicted_total(configs[i].coarse.unit, top_of(configs[i].coarse.unit, kScanUnitTop),
                                        coefficients, r.missing);
    r.unit_error = (unit - configs[i].logic) / configs[i].logic;
    if (!configs[i].coarse.table.empty()) {
      r.has_table = true;
      const double table = predicted_total(configs[i].coarse.table,
                                           top_of(configs[i].coarse.table, "scanline_table"), coefficients,
                                           r.missing);
      r.table_error = (table - configs[i].table) / configs[i].table;
    }
  }

  fmt::print("\nerror of the model's logic area against full synthesis, each configuration left out of "
             "the fit\n{:<17} {:>8} {:>12} {:>11} {:>12} {:>11}\n",
             "design", "configs", "mean |err|", "max |err|", "table mean", "table max");
  nlohmann::json per_design = nlohmann::json::array();
  double worst = 0, sum = 0;
  size_t unpredicted = 0;
  for (const Design& d : designs) {
    double s = 0, m = 0, ts = 0, tm = 0;
    size_t n = 0, tn = 0;
    for (size_t i = 0; i < configs.size(); ++i) {
      if (configs[i].design.name != d.name) continue;
      if (rows[i].missing) {
        ++unpredicted;
        continue;
      }
      ++n;
      s += std::abs(rows[i].unit_error);
      m = std::max(m, std::abs(rows[i].unit_error));
      if (rows[i].has_table) {
        ++tn;
        ts += std::abs(rows[i].table_error);
        tm = std::max(tm, std::abs(rows[i].table_error));
      }
    }
    const double mean = n ? s / static_cast<double>(n) : 0;
    worst = std::max(worst, m);
    sum += s;
    fmt::print("{:<17} {:>8} {:>11.2f}% {:>10.2f}% {:>12} {:>11}\n", d.name, n, 100 * mean, 100 * m,
               tn ? fmt::format("{:.2f}%", 100 * ts / static_cast<double>(tn)) : "-",
               tn ? fmt::format("{:.2f}%", 100 * tm) : "-");
    per_design.push_back({{"design", d.name}, {"configs", n}, {"mean_abs_error", mean}, {"max_abs_error", m},
                          {"table_mean_abs_error", tn ? ts / static_cast<double>(tn) : 0.0},
                          {"table_max_abs_error", tm}});
  }
  const size_t predicted = configs.size() - unpredicted;
  fmt::print("{:<17} {:>8} {:>11.2f}% {:>10.2f}%\n", "all", predicted,
             predicted ? 100 * sum / static_cast<double>(predicted) : 0.0, 100 * worst);
  if (unpredicted)
    fmt::print("{} configurations hold a module kind no other configuration has, so cannot be left out\n",
               unpredicted);

  // The model from every sample.
  const auto coefficients = fit_area_coefficients(samples, std::numeric_limits<size_t>::max());
  nlohmann::json coefficient_json = nlohmann::json::object();
  for (const auto& [kind, c] : coefficients) coefficient_json[kind] = c;
  nlohmann::json configs_json = nlohmann::json::array();
  for (size_t i = 0; i < configs.size(); ++i)
    configs_json.push_back({{"design", configs[i].design.name}, {"widths", describe(configs[i].widths)},
                            {"logic_area_um2", configs[i].logic}, {"flop_table_area_um2", configs[i].table},
                            {"error", rows[i].unit_error}, {"table_error", rows[i].table_error}});
  const nlohmann::json model = {
      {"flow", kCoarseFlow},
      {"features", kAreaFeatures},
      {"coefficients", coefficient_json},
      {"liberty", liberty_name(options.area.liberty)},
      {"rtl_hash", rtl_sources_hash()},
      {"calibration",
       {{"command", fmt::format("cdsim area-model --configs {} --seed {} --design {}", options.configs,
                                options.seed, options.designs)},
        {"build", kBuildRevision},
        {"samples", samples.size()},
        {"per_design", per_design},
        {"configurations", configs_json}}}};
  write_file_atomic(write_path, model.dump(1) + "\n");
  fmt::print("\nwrote {} ({} module kinds, {} module samples)\n", write_path, coefficients.size(),
             samples.size());
  if (!options.json_path.empty()) {
    write_file_atomic(options.json_path, model.at("calibration").dump(2) + "\n");
    fmt::print("wrote {}\n", options.json_path);
  }
  return 0;
}

}  // namespace cdsim
