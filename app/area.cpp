#include "area.hpp"
#include "area_detail.hpp"
#include "area_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <atomic>
#include <map>
#include <mutex>
#include <regex>
#include <sstream>
#include <thread>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <memory>

#include "build_info.hpp"
#include "cache_files.hpp"
#include "area_recovery.hpp"
#include "netlist_writer.hpp"
#include "child_process.hpp"
#include "common.hpp"
#include "derived_widths.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "rtl_sources.hpp"
#include "sta.hpp"

namespace cdsim {

namespace fs = std::filesystem;

namespace {

// Bumped whenever the flow below changes, so that cached results are redone.
constexpr const char* kFlowVersion = "area-flow-7";
// And of the recovering flow on top of it (`--flow recover`).
constexpr const char* kRecoverFlowVersion = "recover-5";

// Yosys writes "=== cd_scan_unit ===" but "Chip area for module '\cd_scan_unit'".
std::string strip_escape(const std::string& name) {
  return !name.empty() && name[0] == '\\' ? name.substr(1) : name;
}

// "$paramod$0123\shift_round", "$paramod\setup_engine\SramDepth=..." and
// "\column_walker" all name a module by the part after the first backslash.
}  // namespace

namespace area_detail {

std::string base_name(const std::string& module) {
  const size_t slash = module.find('\\');
  if (slash == std::string::npos) return module;
  const std::string rest = module.substr(slash + 1);
  return rest.substr(0, rest.find('\\'));
}

std::map<std::string, ModuleStat> parse_stat(const std::string& log) {
  std::map<std::string, ModuleStat> modules;
  // Only the last statistics (the mapped netlist) count.
  const size_t last = log.rfind("Printing statistics.");
  std::istringstream in(last == std::string::npos ? log : log.substr(last));
  std::string line, current;
  bool in_cells = false;
  static const std::regex header(R"(^=== (.+) ===$)");
  static const std::regex cell(R"(^\s+(\S+)\s+(\d+)$)");
  static const std::regex area(R"(^\s+Chip area for module '(.+)': ([0-9.eE+-]+)$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, header)) {
      current = strip_escape(m[1]);
      modules[current];
      in_cells = false;
    } else if (line.find("Number of cells:") != std::string::npos) {
      in_cells = !current.empty();
    } else if (std::regex_match(line, m, area)) {
      modules[strip_escape(m[1])].own_area = std::stod(m[2]);
      in_cells = false;
    } else if (in_cells && std::regex_match(line, m, cell)) {
      const std::string type = strip_escape(m[1]);
      const int64_t count = std::stoll(m[2]);
      if (type.rfind("DFF", 0) == 0) modules[current].own_flops += count;
      modules[current].cells[type] += count;
    } else if (line.find("design hierarchy") != std::string::npos) {
      break;
    }
  }
  for (auto& [name, stat] : modules)
    for (const auto& [type, count] : stat.cells)
      if (modules.count(type)) stat.submodules[type] = count;
  return modules;
}

std::map<std::string, Multiply> parse_multiplies(const std::string& dump) {
  std::map<std::string, Multiply> out;
  std::istringstream in(dump);
  std::string line, module;
  Multiply cell;
  bool in_mul = false;
  static const std::regex module_line(R"(^module (\S+)$)");
  static const std::regex cell_line(R"(^\s*cell (\S+) )");
  static const std::regex width(R"(^\s*parameter \\([ABY])_WIDTH (\d+)$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_match(line, m, module_line)) {
      module = strip_escape(m[1]);
    } else if (std::regex_search(line, m, cell_line)) {
      in_mul = m[1] == "$mul";
      cell = {};
    } else if (in_mul && std::regex_match(line, m, width)) {
      (m[1] == "A" ? cell.a : m[1] == "B" ? cell.b : cell.product) = std::stoi(m[2]);
    } else if (in_mul && line.find_first_not_of(' ') != std::string::npos &&
               line.substr(line.find_first_not_of(' ')) == "end") {
      if (cell.wider_than(out[module])) out[module] = cell;
      in_mul = false;
    }
  }
  return out;
}

namespace {

struct Subtree {
  double area = 0;
  int64_t flops = 0;
};

Subtree subtree(const std::map<std::string, ModuleStat>& modules, const std::string& name) {
  Subtree total;
  const auto it = modules.find(name);
  if (it == modules.end()) return total;
  total.area = it->second.own_area;
  total.flops = it->second.own_flops;
  for (const auto& [sub, count] : it->second.submodules) {
    const Subtree s = subtree(modules, sub);
    total.area += static_cast<double>(count) * s.area;
    total.flops += count * s.flops;
  }
  return total;
}

std::string find_module(const std::map<std::string, ModuleStat>& modules, const std::string& base) {
  for (const auto& [name, stat] : modules)
    if (base_name(name) == base) return name;
  throw std::runtime_error(fmt::format("yosys statistics list no module '{}'", base));
}

// The widest multiply in a module's subtree (the hierarchy of `modules`),
// submodules of base name `skip` left out (the reciprocal, a block of its own).
Multiply widest_multiply(const std::map<std::string, ModuleStat>& modules,
                         const std::map<std::string, Multiply>& own, const std::string& name,
                         const std::string& skip = "") {
  Multiply widest;
  if (const auto m = own.find(name); m != own.end()) widest = m->second;
  const auto it = modules.find(name);
  if (it == modules.end()) return widest;
  for (const auto& [sub, count] : it->second.submodules) {
    if (base_name(sub) == skip) continue;
    const Multiply w = widest_multiply(modules, own, sub, skip);
    if (w.wider_than(widest)) widest = w;
  }
  return widest;
}

// The module's subtree, or nothing when the design does not have it.
Subtree subtree_of(const std::map<std::string, ModuleStat>& modules, const std::string& base) {
  for (const auto& [name, stat] : modules)
    if (base_name(name) == base) return subtree(modules, name);
  return {};
}

double liberty_cell_area(const std::string& liberty, const std::string& cell) {
  const std::string text = read_text_file(liberty);
  const std::regex pattern("cell \\(" + cell + "\\) \\{\\s*area : ([0-9.]+)");
  std::smatch m;
  if (!std::regex_search(text, m, pattern))
    throw std::runtime_error(fmt::format("{}: no area for cell {}", liberty, cell));
  return std::stod(m[1]);
}

}  // namespace

void run_yosys(const std::vector<YosysRun>& runs) {
  std::vector<std::unique_ptr<ChildProcess>> children;
  for (const YosysRun& run : runs)
    children.push_back(std::make_unique<ChildProcess>(
        std::vector<std::string>{"yosys", "-q", "-l", run.log.string(), "-s", run.script.string()},
        "/dev/null"));
  std::vector<int> statuses(runs.size(), -1);
  for (size_t left = runs.size(); left > 0;) {
    throw_if_interrupted();  // the destructors stop the groups
    for (size_t i = 0; i < runs.size(); ++i)
      if (statuses[i] == -1 && children[i]->finished(statuses[i])) --left;
    if (left > 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (size_t i = 0; i < runs.size(); ++i)
    if (!(WIFEXITED(statuses[i]) && WEXITSTATUS(statuses[i]) == 0))
      throw std::runtime_error(fmt::format("yosys failed {}: {} ({}, {})", runs[i].what, yosys_error(runs[i].log),
                                           describe_status(statuses[i]), runs[i].log.string()));
}

std::string yosys_error(const fs::path& log) {
  std::ifstream in(log);
  std::string line, error;
  while (std::getline(in, line))
    if (line.find("ERROR") != std::string::npos || line.find("Assertion failed") != std::string::npos)
      error = line;
  return error.empty() ? "see the log" : error;
}

}  // namespace area_detail

using namespace area_detail;

namespace area_detail {

std::vector<fs::path> rtl_sources_of(const std::string& top) {
  std::vector<fs::path> sources;
  for (const char* file : kScanUnitRtlFiles) sources.push_back(fs::path(kRtlDir) / file);
  if (top == kAdaptiveUnitTop)
    for (const char* file : kAdaptiveRtlFiles) sources.push_back(fs::path(kRtlDir) / file);
  std::sort(sources.begin(), sources.end());
  return sources;
}

UnitConfig prepare_unit(const Design& design, const Widths& widths, const AreaOptions& options) {
  if (!has_rtl(design))
    throw std::invalid_argument(fmt::format(
        "design '{}' has no RTL yet; cdsim area synthesises {}", design.name, rtl_design_names()));
  validate(widths);
  if (!fs::exists(options.liberty))
    throw std::runtime_error(fmt::format(
        "{}: no such liberty file (scripts/setup installs qflow-tech-osu018)", options.liberty));
  UnitConfig c;
  const DerivedWidths derived = derive(widths);
  // The unit elaborated with this design's hardware only (rtl/cd_scan_unit.sv),
  // or the adaptive design's unit (rtl/adaptive_unit.sv: its split engine and
  // an affine-only scan unit, elaborated by the unit itself, at the leaves' widths).
  c.top = rtl_top(design) == RtlTop::AdaptiveUnit ? kAdaptiveUnitTop : kScanUnitTop;
  c.has_table = design.kind == Design::Kind::ConstantDepth;
  const bool has_divide = design.kind == Design::Kind::Divide;
  const bool has_sub = design.kind == Design::Kind::Affine && design.subdivision != 0;
  // The reciprocal, reported on its own, is the fill's (in the setup engine)
  // in the table designs, the pixels' (in pixel_divide) in divide and the
  // exact points' in affine-subN and quad-subN.
  // The adaptive design's is its split engine's (the midpoints' 1/q).
  c.reciprocal_owner = c.has_table ? "setup_engine" : has_divide ? "pixel_divide"
                       : has_sub ? "exact_points" : c.top == kAdaptiveUnitTop ? "adaptive_split" : "";
  std::string parameters;
  if (c.top == kScanUnitTop)
    for (const UnitParameter& p : unit_parameters({&design}))
      parameters += fmt::format("-set {} {} ", p.name, p.value);
  parameters += "-set HasObservation 0";

  // The top's RTL sources (those the simulations verilate), in name order, so
  // that the hash is stable and a change to the other unit's files keeps
  // this one's syntheses.
  const std::vector<fs::path> sources = rtl_sources_of(c.top);
  c.header = c.top == kAdaptiveUnitTop ? rtl_header(adaptive_leaf_widths(widths), "area, adaptive leaf unit")
                                      : rtl_header(widths, "area");
  uint64_t hash = fnv1a(kFlowVersion);
  if (options.flow == "recover") hash = fnv1a(kRecoverFlowVersion, hash);
  else if (options.flow != "delay")
    throw std::invalid_argument(fmt::format("--flow {}: not a flow (delay, recover)", options.flow));
  hash = fnv1a(c.header, hash);
  hash = fnv1a(fmt::format("{} {} {}", c.top, parameters, options.liberty), hash);
  if (options.clock_mhz > 0) hash = fnv1a(fmt::format("clock {}", options.clock_mhz), hash);
  for (const fs::path& source : sources) hash = fnv1a(read_text_file(source), hash);

  const fs::path cache = options.cache_dir.empty() ? cache_root("area") : fs::path(options.cache_dir);
  check_cache_folder(cache, options.cache_dir.empty() ? "the area cache" : "--cache");
  c.dir = fs::absolute(cache) / fmt::format("{:016x}", hash);
  c.bank_depth = c.has_table ? int64_t{widths.table_depth} << log2_ceil(design.density) : 0;
  c.sram_depth = c.bank_depth * widths.table_banks;
  c.word_bits = unit_word_bits(derived, design.persp);
  c.flop_lines = std::min<int64_t>(c.sram_depth, 64);  // 0: no table
  for (const fs::path& source : sources)
    if (source.filename() != "scanline_table.sv") c.unit_sources += " " + source.string();
  c.parameters = parameters;
  return c;
}

std::string UnitConfig::unit_front(const fs::path& include) const {
  const std::string rtl_dir = kRtlDir;
  return fmt::format(
      "read_verilog -sv -DSYNTHESIS {inc}{src}\n"
      "read_verilog -sv -lib {inc} {rtl}/scanline_table.sv\n"
      "chparam {p} {top}\n"
      "hierarchy -check -top {top}\n"
      // The setup engine's stage modules are synthesised as part of it, as
      // one block (flattened into setup_engine, so that constants and unused
      // outputs cross their ports); every other module keeps its own.
      "setattr -mod -set keep_hierarchy 1 *\n"
      "setattr -mod -unset keep_hierarchy *setup_stage_* *setup_dividers* *setup_fill*\n"
      "flatten\n"
      "setattr -mod -unset keep_hierarchy *\n",
      fmt::arg("inc", fmt::format("-I{} -I{}", include.string(), rtl_dir)), fmt::arg("src", unit_sources),
      fmt::arg("rtl", rtl_dir), fmt::arg("p", parameters), fmt::arg("top", top));
}

std::string UnitConfig::table_front(const fs::path& include) const {
  const std::string rtl_dir = kRtlDir;
  return fmt::format(
      "read_verilog -sv {inc} {rtl}/scanline_table.sv\n"
      "chparam -set Depth {d} -set WordBits {w} scanline_table\n"
      "hierarchy -check -top scanline_table\n",
      fmt::arg("inc", fmt::format("-I{} -I{}", include.string(), rtl_dir)), fmt::arg("rtl", rtl_dir),
      fmt::arg("d", flop_lines), fmt::arg("w", word_bits));
}

EntryLock::EntryLock(const UnitConfig& config, const std::string& what)
    : lock_(config.dir.string() + ".lock", what) {}

std::optional<nlohmann::json> cached_result(const UnitConfig& config, const std::string& name,
                                            const std::function<std::string(const nlohmann::json&)>& check) {
  const fs::path path = config.dir / name;
  const fs::path manifest = config.dir / (name + ".manifest");
  std::error_code ec;
  if (!fs::exists(path, ec) && !fs::exists(manifest, ec)) return std::nullopt;
  std::string wrong = fs::exists(manifest, ec) ? verify_manifest(manifest, config.dir)
                                              : "no manifest: built by an older cdsim";
  nlohmann::json j;
  if (wrong.empty()) {
    try {
      j = read_json_file(path);
      wrong = check(j);
    } catch (const std::exception& e) {
      wrong = e.what();
    }
  }
  if (wrong.empty()) return j;
  std::cerr << fmt::format("area: the cached {} is corrupt ({}); building it again\n", path.string(), wrong);
  fs::remove(path, ec);
  fs::remove(manifest, ec);
  return std::nullopt;
}

void build_result(const UnitConfig& config, const std::string& name,
                  const std::function<void(const fs::path& work)>& build) {
  static std::atomic<unsigned> counter{0};
  const fs::path cache = config.dir.parent_path();
  const std::string key = config.dir.filename().string();
  std::error_code ec;
  // Work folders that a killed cdsim left: this entry's at once (no one else
  // builds it: the caller holds its lock), the others' after a day.
  const auto day_ago = fs::file_time_type::clock::now() - std::chrono::hours(24);
  for (const auto& entry : fs::directory_iterator(cache, ec)) {
    const std::string file = entry.path().filename().string();
    if (file.rfind("tmp-" + key + "-", 0) == 0 || (file.rfind("tmp-", 0) == 0 && entry.last_write_time(ec) < day_ago))
      fs::remove_all(entry.path(), ec);
  }
  const fs::path work = cache / fmt::format("tmp-{}-{}-{}", key, ::getpid(), counter++);
  RemoveOnExit remove_work(work);
  fs::create_directory(work);
  write_file_atomic(work / "cd_widths.svh", config.header);
  try {
    build(work);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    // The logs outlive the work folder, for the message to name them.
    const fs::path kept = cache / ("failed-" + key);
    fs::remove_all(kept, ec);
    fs::create_directory(kept, ec);
    for (const auto& entry : fs::directory_iterator(work, ec))
      if (const fs::path ext = entry.path().extension(); ext == ".log" || ext == ".ys" || ext == ".v" || ext == ".tcl")
        fs::copy_file(entry.path(), kept / entry.path().filename(), ec);
    std::string message = e.what();
    for (size_t at; (at = message.find(work.string())) != std::string::npos;)
      message.replace(at, work.string().size(), kept.string());
    throw std::runtime_error(message);
  }
  if (::mkdir(config.dir.c_str(), 0700) != 0 && errno != EEXIST)
    throw std::runtime_error(fmt::format("{}: cannot create the cache entry: {}", config.dir.string(), std::strerror(errno)));
  for (const auto& entry : fs::directory_iterator(work))
    if (entry.path().filename() != name) fs::rename(entry.path(), config.dir / entry.path().filename());
  // The manifest before the result: a result without one is never used.
  const std::string manifest = config.dir / (name + ".manifest");
  write_manifest(work / "manifest", work, {work / name});
  fs::rename(work / "manifest", manifest);
  fs::rename(work / name, config.dir / name);
  fs::remove_all(cache / ("failed-" + key), ec);
}

namespace {

std::string finite_non_negative(const nlohmann::json& j, const char* key) {
  if (!j.contains(key)) return fmt::format("no '{}'", key);
  const nlohmann::json& v = j.at(key);
  if (!v.is_number()) return fmt::format("'{}' is not a number", key);
  const double x = v.get<double>();
  if (!std::isfinite(x) || x < 0) return fmt::format("'{}' is {}, not a finite number >= 0", key, v.dump());
  return "";
}

}  // namespace

std::string check_synthesis(const nlohmann::json& j) {
  if (!j.is_object()) return "not a JSON object";
  for (const char* key : {"seconds", "flop_table_lines", "flop_table_area_um2"})
    if (std::string wrong = finite_non_negative(j, key); !wrong.empty()) return wrong;
  if (!j.contains("blocks") || !j.at("blocks").is_array()) return "'blocks' is not a list";
  for (const nlohmann::json& b : j.at("blocks")) {
    if (!b.is_object() || !b.contains("name") || !b.at("name").is_string()) return "a block without a name";
    for (const char* key : {"area_um2", "flops", "mul_a_bits", "mul_b_bits", "mul_product_bits"})
      if (std::string wrong = finite_non_negative(b, key); !wrong.empty())
        return fmt::format("block '{}': {}", b.at("name").get<std::string>(), wrong);
  }
  if (!j.contains("timing") || !j.at("timing").is_object()) return "no 'timing'";
  const nlohmann::json& t = j.at("timing");
  if (std::string wrong = finite_non_negative(t, "critical_path_ns"); !wrong.empty()) return "timing: " + wrong;
  if (t.at("critical_path_ns").get<double>() <= 0) return "timing: a critical path of no length";
  for (const char* key : {"critical_path_from", "critical_path_to"})
    if (!t.contains(key) || !t.at(key).is_string()) return fmt::format("timing: no '{}'", key);
  if (!t.contains("block_critical_path_ns") || !t.at("block_critical_path_ns").is_object())
    return "timing: no 'block_critical_path_ns'";
  for (const auto& [name, v] : t.at("block_critical_path_ns").items())
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() <= 0)
      return fmt::format("timing: block '{}' has critical path {}", name, v.dump());
  return "";
}

std::string block_of_module(const std::string& base) {
  static const std::map<std::string, std::string> block_of = {
      {"setup_engine", "setup engine"},     {"column_walker", "column walker"},
      {"correction_adder", "correction adder"}, {"plane_accumulator", "plane accumulators"},
      {"pixel_divide", "pixel multiply"},   {"affine_setup", "affine setup"},
      {"shift_round", "output rounding"},   {"affine_sub_datapath", "subdivision datapath"},
      {"quad_sub_datapath", "subdivision datapath"}, {"exact_points", "exact points"},
      {"kim_datapath", "Kim datapath"},     {"context_register", "contexts"},
      {"adaptive_split", "split engine"}, {"scanline_table", "scanline table"}};
  const auto it = block_of.find(base);
  return it == block_of.end() ? "" : it->second;
}

std::string block_of_pin(const std::map<std::string, std::string>& instance_module, const std::string& pin) {
  // The instances that hold the pin's cell, outermost first: "a/b/_12_/D"
  // lies in "a" and "a/b".
  std::vector<std::string> bases;
  for (size_t slash = pin.find('/'); slash != std::string::npos; slash = pin.find('/', slash + 1)) {
    const auto it = instance_module.find(pin.substr(0, slash));
    if (it != instance_module.end()) bases.push_back(base_name(it->second));
  }
  // As block_areas counts them: a reciprocal apart from the block that holds
  // it, the adaptive unit's leaf unit looked through, the top's own cells as
  // control.
  if (std::find(bases.begin(), bases.end(), "reciprocal") != bases.end()) return "reciprocal";
  // The table's timing model, flattened into the unit: "gen_table...u_scanline_table.d_own_addr_i_0/D".
  if (pin.find("u_scanline_table.") != std::string::npos) return "scanline table";
  for (const std::string& base : bases)
    if (base != kScanUnitTop) {
      const std::string block = block_of_module(base);
      return block.empty() ? base : block;
    }
  return "control";
}

namespace {

// The worst path of the unit and of each block, as result.json keeps them.
nlohmann::json block_timing(const StaReport& sta, const std::string& netlist) {
  std::map<std::string, double> worst;
  for (const StaEndpoint& e : sta.endpoints) {
    double& w = worst[block_of_pin(sta.instance_module, e.pin)];
    w = std::max(w, e.period_ns);
  }
  if (sta.endpoints.empty()) throw std::runtime_error(fmt::format("area: OpenSTA timed no flip-flop in {}", netlist));
  return {{"critical_path_ns", sta.endpoints.front().period_ns},
          {"critical_path_from", sta.worst_from},
          {"critical_path_to", sta.worst_to},
          {"block_critical_path_ns", worst},
          {"flops_timed", sta.endpoints.size()},
          {"sta_seconds", sta.seconds}};
}

}  // namespace

nlohmann::json block_areas(const std::map<std::string, ModuleStat>& unit, const UnitConfig& config,
                           const std::string& log_path, const std::map<std::string, Multiply>& multiplies) {
  // Blocks: the scan unit's submodules by kind (the table is a black box),
  // each reciprocal counted apart from the block that holds it, and the
  // unit's own cells as control. They sum to the unit's logic. The adaptive
  // design's unit adds its split engine, and its own cells (the records) to
  // control.
  const Subtree recip = subtree_of(unit, "reciprocal");  // one per design: fill, pixels or midpoints
  std::vector<std::string> order;
  std::map<std::string, Subtree> totals;
  std::map<std::string, Multiply> widest;
  const auto add = [&](const std::string& name, double area, int64_t flops, const Multiply& multiply) {
    if (!totals.count(name)) order.push_back(name);
    totals[name].area += area;
    totals[name].flops += flops;
    if (multiply.wider_than(widest[name])) widest[name] = multiply;
  };
  const std::function<void(const std::string&)> add_blocks = [&](const std::string& top) {
    for (const auto& [sub, count] : unit.at(top).submodules) {
      const std::string base = base_name(sub);
      if (base == "scanline_table") continue;
      if (base == kScanUnitTop) {  // the adaptive unit's leaf unit
        add_blocks(sub);
        continue;
      }
      const std::string block = block_of_module(base);
      if (block.empty())
        throw std::runtime_error(fmt::format("area: no block for module '{}' in {}", base, log_path));
      Subtree t = subtree(unit, sub);
      const bool owner = base == config.reciprocal_owner;
      if (owner) {
        t.area -= recip.area;
        t.flops -= recip.flops;
      }
      add(block, static_cast<double>(count) * t.area, count * t.flops,
          widest_multiply(unit, multiplies, sub, owner ? "reciprocal" : ""));
    }
    const auto& control = unit.at(top);
    const auto own = multiplies.find(top);
    add("control", control.own_area, control.own_flops, own == multiplies.end() ? Multiply{} : own->second);
  };
  add_blocks(find_module(unit, config.top));
  if (recip.area > 0) {
    Multiply recip_widest;
    for (const auto& [name, stat] : unit)
      if (base_name(name) == "reciprocal")
        if (const Multiply w = widest_multiply(unit, multiplies, name); w.wider_than(recip_widest)) recip_widest = w;
    add("reciprocal", recip.area, recip.flops, recip_widest);
  }
  nlohmann::json blocks = nlohmann::json::array();
  for (const std::string& name : order)
    blocks.push_back({{"name", name}, {"area_um2", totals[name].area}, {"flops", totals[name].flops},
                      {"mul_a_bits", widest[name].a}, {"mul_b_bits", widest[name].b},
                      {"mul_product_bits", widest[name].product}});
  return blocks;
}

double table_area(const std::map<std::string, ModuleStat>& table) {
  return subtree(table, find_module(table, "scanline_table")).area;
}

AreaReport area_report(const Design& design, const Widths& widths, const UnitConfig& config,
                       const nlohmann::json& synthesised, const AreaOptions& options) {
  AreaReport report;
  report.design = design.name;
  report.widths = widths;
  report.log_path = (config.dir / "unit.log").string();
  report.sram_bits = config.sram_depth * config.word_bits;
  report.sram_two_port = report.sram_bits > 0 && widths.early_walk != 0;
  report.sram_area_um2 = static_cast<double>(report.sram_bits) * options.sram_cell_um2 *
                         (report.sram_two_port ? options.sram_two_port_factor : 1.0) / options.sram_efficiency;
  const double nand2 = liberty_cell_area(options.liberty, "NAND2X1");
  report.synthesis_seconds = synthesised.at("seconds").get<double>();
  for (const auto& b : synthesised.at("blocks")) {
    if (b.at("area_um2").get<double>() == 0 && b.at("flops").get<int64_t>() == 0) continue;  // absent
    BlockArea block;
    block.name = b.at("name").get<std::string>();
    block.area_um2 = b.at("area_um2").get<double>();
    block.flops = b.at("flops").get<int64_t>();
    block.mul_a_bits = b.at("mul_a_bits").get<int>();
    block.mul_b_bits = b.at("mul_b_bits").get<int>();
    block.mul_product_bits = b.at("mul_product_bits").get<int>();
    block.nand2_eq = block.area_um2 / nand2;
    report.logic_area_um2 += block.area_um2;
    report.blocks.push_back(block);
  }
  if (synthesised.contains("timing")) {  // the component model's estimates are not timed
    const nlohmann::json& t = synthesised.at("timing");
    report.critical_path_ns = t.at("critical_path_ns").get<double>();
    report.fmax_mhz = 1000.0 / report.critical_path_ns;
    report.critical_path_from = t.at("critical_path_from").get<std::string>();
    report.critical_path_to = t.at("critical_path_to").get<std::string>();
    report.timing_report_path = (config.dir / "timing.rpt").string();
    const nlohmann::json& per_block = t.at("block_critical_path_ns");
    for (BlockArea& block : report.blocks)
      if (per_block.contains(block.name)) block.critical_path_ns = per_block.at(block.name).get<double>();
    if (per_block.contains("scanline table")) report.table_path_ns = per_block.at("scanline table").get<double>();
  }
  report.flow = synthesised.value("flow", "delay");
  if (synthesised.contains("recovery")) {
    const nlohmann::json& r = synthesised.at("recovery");
    report.recovery_target_ns = r.at("target_ns").get<double>();
    report.area_mapped_modules = r.at("area_mapped").size();
    report.modules = r.at("modules").get<size_t>();
    report.delay_mapped_logic_um2 = r.at("delay_mapped_logic_um2").get<double>();
    report.area_mapped_logic_um2 = r.at("area_mapped_logic_um2").get<double>();
  }
  report.flop_table_lines_synthesised = synthesised.at("flop_table_lines").get<int64_t>();
  if (report.flop_table_lines_synthesised > 0)
    report.flop_table_area_um2 = synthesised.at("flop_table_area_um2").get<double>() *
                                 static_cast<double>(config.sram_depth) /
                                 static_cast<double>(report.flop_table_lines_synthesised);
  report.total_area_um2 = report.logic_area_um2 + report.sram_area_um2;
  return report;
}

// ABC's fast mapping (Yosys's `abc -fast` script: strash; dretime; map), then
// what a designer's flow adds before timing: buffers on the nets of more
// than 16 loads (without them a stage enable drives thousands of gate inputs
// from one X1 cell, and the timing is microseconds), and gates off the
// critical path sized down again. Given a clock, the mapping and the sizing
// aim at its period (ABC's -D, in ps). docs/area.md, "Timing".
void write_abc_script(const fs::path& work, double clock_mhz) {
  write_file_atomic(work / "abc.constr", "set_driving_cell BUFX2\nset_load 0.02\n");
  const std::string target = clock_mhz > 0 ? fmt::format(" -D {:.0f}", 1e6 / clock_mhz) : "";
  write_file_atomic(work / "abc.script",
                    fmt::format("read_constr -v {}\nstrash\ndretime\nmap{t}\ntopo\nbuffer -N 16\ntopo\n{up}dnsize{t}\n",
                                (work / "abc.constr").string(), fmt::arg("t", target),
                                fmt::arg("up", clock_mhz > 0 ? "upsize" + target + "\ntopo\n" : "")));
}

// The area corner of the recovering flow (`--flow recover`, docs/area.md):
// the AIG compressed (dc2), mapped over structural choices (&dch) by ABC's
// area-oriented mapper (&nf), then buffered and sized as abc.script is. On the
// column walker at default widths it maps 264,121 um^2 where abc.script maps
// 378,730, with a 9.06 ns path against 4.29 (docs/area.md).
void write_area_abc_script(const fs::path& work) {
  write_file_atomic(work / "abc_area.script",
                    fmt::format("read_constr -v {}\nstrash\ndc2\n&get -n\n&dch -f\n&nf\n&put\ntopo\nbuffer -N 16\n"
                                "topo\ndnsize\n", (work / "abc.constr").string()));
}

}  // namespace area_detail

namespace {

// The scanline table as OpenSTA sees it (osu018 has no SRAM macro, so no
// timing model): one flip-flop per port bit, read data leaving a Q at the
// clock edge (the table reads synchronously), every input ending at a D.
// Optimistic by the macro's access time less a flip-flop's clock to Q.
// Flattened into the unit after the statistics, so it adds no area.
std::string table_timing_model(const UnitConfig& config) {
  const int addr_bits = std::max(1, log2_ceil(static_cast<int>(config.bank_depth)));
  const int word = config.word_bits;
  struct Port {
    const char* name;
    int bits;
    bool output;
  };
  const Port ports[] = {{"clk_i", 1, false},          {"write_i", 1, false},
                        {"write_addr_i", addr_bits, false}, {"write_entry_i", word, false},
                        {"read_i", 1, false},         {"own_addr_i", addr_bits, false},
                        {"neighbour_read_i", 1, false}, {"neighbour_addr_i", addr_bits, false},
                        {"own_entry_o", word, true},  {"neighbour_entry_o", word, true}};
  std::string names, declarations, cells;
  for (const Port& p : ports) {
    names += std::string(names.empty() ? "" : ", ") + p.name;
    declarations += fmt::format("  {} {}{};\n", p.output ? "output" : "input",
                                p.bits > 1 ? fmt::format("[{}:0] ", p.bits - 1) : "", p.name);
    if (std::string(p.name) == "clk_i") continue;
    for (int i = 0; i < p.bits; ++i) {
      const std::string bit = p.bits > 1 ? fmt::format("{}[{}]", p.name, i) : p.name;
      cells += p.output ? fmt::format("  DFFPOSX1 q_{}_{} (.CLK(clk_i), .D(1'b0), .Q({}));\n", p.name, i, bit)
                        : fmt::format("  DFFPOSX1 d_{}_{} (.CLK(clk_i), .D({}), .Q());\n", p.name, i, bit);
    }
  }
  return fmt::format("// cdsim area: the scanline table's timing model (app/area.cpp, table_timing_model)\n"
                     "module scanline_table({});\n{}{}endmodule\n", names, declarations, cells);
}

}  // namespace

AreaReport synthesise_area(const Design& design, const Widths& widths, const AreaOptions& options) {
  // The component model is calibrated on the scan unit's designs: the
  // adaptive design's unit, with its split engine, is always synthesised.
  if (options.estimate && options.flow != "delay")
    throw std::invalid_argument(fmt::format("the component area model is calibrated on the delay flow, not the {} "
                                            "flow: synthesise instead (without --model / --area-model)",
                                            options.flow));
  if (options.estimate && rtl_top(design) == RtlTop::ScanUnit) return estimate_area(design, widths, options);
  if (options.estimate && !options.quiet)
    std::cerr << fmt::format("area: {}: the component model does not cover its unit; synthesising it\n",
                             design.name);
  const UnitConfig config = prepare_unit(design, widths, options);
  const EntryLock lock(config, fmt::format("area: {} at {}", design.name, describe(widths)));
  std::optional<nlohmann::json> synthesised = cached_result(config, "result.json", check_synthesis);
  const bool cached = synthesised.has_value();
  if (!cached) build_result(config, "result.json", [&](const fs::path& work) {
    const std::string& L = options.liberty;
    write_abc_script(work, options.clock_mhz);
    const bool recover = options.flow == "recover";
    if (recover) write_area_abc_script(work);
    // After the flip-flops are mapped: the logic onto the liberty's gates by
    // `script`, the statistics, and the netlist OpenSTA times: no undriven
    // bit, the table's timing model in place of the black box, one-bit
    // ports; as JSON, which app/netlist_writer.cpp writes as Verilog (Yosys
    // 0.23's write_verilog took 56 s of a 140 s synthesis, write_json 1 s).
    const auto map_logic = [&](const std::string& script, const std::string& json) {
      return fmt::format(
          "abc -liberty {L} -script {W}/{script}\nopt_clean\n"
          "select -assert-none t:$* t:$paramod* %d\n"
          "stat -liberty {L}\n"
          "setundef -zero\n{table}splitnets -ports\nopt_clean -purge\n"
          "write_json {W}/{json}\n", fmt::arg("L", options.liberty), fmt::arg("W", work.string()),
          fmt::arg("script", script), fmt::arg("json", json),
          fmt::arg("table", config.has_table ? fmt::format(
              "setparam -unset Depth -unset WordBits t:scanline_table\n"
              "read_verilog -overwrite {W}/table_timing.v\n"
              "setattr -mod -set keep_hierarchy 1 *\nsetattr -mod -unset keep_hierarchy scanline_table\n"
              "flatten\nsetattr -mod -unset keep_hierarchy *\n", fmt::arg("W", work.string())) : ""));
    };
    // The recovering flow also flattens the rounding shifters (shift_round)
    // into the modules that use them, but the top's (its "output rounding"
    // block): most shift by a constant, which crosses no port, and the
    // correction adder at narrow widths maps 13% smaller flattened
    // (docs/area.md, "Area recovery").
    const std::string flatten_rounding =
        recover ? fmt::format("setattr -mod -set keep_hierarchy 1 *\nsetattr -mod -unset keep_hierarchy *shift_round*\n"
                              "flatten {} %n\nsetattr -mod -unset keep_hierarchy *\n", config.top)
                : "";
    write_file_atomic(work / "unit.ys", config.unit_front(work) + flatten_rounding + fmt::format(
        "proc\n"
        "select -assert-none t:$dlatch t:$adlatch t:$dlatchsr t:$sr\n"
        "{opt}\n"
        "select -assert-none t:$div t:$mod t:$divfloor t:$modfloor\n"
        "wreduce\ntee -q -o {W}/multiplies.il dump t:$mul\n{coarse}memory -nomap\n{after}techmap\n"
        "dfflibmap -liberty {L}\n", fmt::arg("L", L), fmt::arg("W", work.string()),
        // The recovering flow runs synth's coarse word-level passes (the
        // column walker at narrow widths maps 7% smaller with them).
        fmt::arg("opt", recover ? "opt" : "opt -fast"),
        fmt::arg("coarse", recover ? "peepopt\nopt_clean\nalumacc\nshare\nopt\n" : "alumacc\nopt -fast\n"),
        fmt::arg("after", recover ? "opt_clean\nopt -fast -full\n" : "")) +
        (recover ? "design -save flops_mapped\n" + map_logic("abc.script", "unit_delay.json") +
                   "design -load flops_mapped\n" + map_logic("abc_area.script", "unit.json")
                 : map_logic("abc.script", "unit.json")));
    if (config.has_table) write_file_atomic(work / "table_timing.v", table_timing_model(config));
    write_file_atomic(work / "table.ys", config.table_front(work) + fmt::format(
        "proc\nopt -fast\nmemory\nopt -fast\ntechmap\n"
        "dfflibmap -liberty {L}\nabc -liberty {L} -script {W}/abc.script\nopt_clean\n"
        "select -assert-none t:$* t:$paramod* %d\n"
        "stat -liberty {L}\n", fmt::arg("L", L), fmt::arg("W", work.string())));

    if (!options.quiet)
      std::cerr << fmt::format("area: synthesising {} with yosys onto {} (entry {})\n", design.name,
                               fs::path(L).filename().string(), config.dir.string());
    const auto start = std::chrono::steady_clock::now();
    std::vector<YosysRun> runs = {{work / "unit.ys", work / "unit.log", "on the unit"}};
    if (config.has_table) runs.push_back({work / "table.ys", work / "table.log", "on the flip-flop table"});
    run_yosys(runs);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string log = read_text_file(work / "unit.log");
    const auto multiplies = parse_multiplies(read_text_file(work / "multiplies.il"));
    const std::string log_path = (work / "unit.log").string();
    const auto logic_of = [&](const std::map<std::string, ModuleStat>& stat) {
      double sum = 0;
      for (const auto& b : block_areas(stat, config, log_path, multiplies)) sum += b.at("area_um2").get<double>();
      return sum;
    };
    std::map<std::string, ModuleStat> unit = parse_stat(log);  // the last mapping's: the area mapping's
    StaReport sta;
    nlohmann::json recovery;
    std::error_code ec;
    if (recover) {
      const auto modules_of = [&](const fs::path& json) {
        const ModuleTexts texts = verilog_modules_from_yosys_json(nlohmann::json::parse(read_text_file(json)));
        fs::remove(json, ec);  // tens of megabytes
        return texts;
      };
      const ModuleTexts delay_texts = modules_of(work / "unit_delay.json");
      const ModuleTexts area_texts = modules_of(work / "unit.json");
      const Recovery r = recover_area(delay_texts, area_texts, options.clock_mhz > 0 ? 1000 / options.clock_mhz : 0,
                                      config.top, L, "clk_i", work, [&](const std::string& line) {
                                        if (!options.quiet) std::cerr << line << "\n";
                                      });
      const std::map<std::string, ModuleStat> delay_unit = parse_stat(log.substr(0, log.rfind("Printing statistics.")));
      const std::map<std::string, ModuleStat> area_unit = unit;
      for (auto& [name, stat] : unit) {
        if (r.area_modules.count(name)) continue;
        const auto it = delay_unit.find(name);
        if (it == delay_unit.end())
          throw std::runtime_error(fmt::format("area: module {} has no delay-mapped statistics in {}", name, log_path));
        stat = it->second;
      }
      recovery = {{"target_ns", r.target_ns}, {"rounds", r.rounds}, {"fell_back", r.fell_back},
                  {"modules", r.modules}, {"area_mapped", r.area_modules},
                  {"delay_mapped_logic_um2", logic_of(delay_unit)}, {"area_mapped_logic_um2", logic_of(area_unit)},
                  {"delay_mapped_critical_path_ns", r.delay.endpoints.front().period_ns}};
      sta = r.chosen;
    } else {
      write_verilog_from_yosys_json(work / "unit.json", work / "unit.v");
      fs::remove(work / "unit.json", ec);  // tens of megabytes
      sta = time_netlist({work / "unit.v"}, config.top, L, "clk_i", work);
    }
    write_file_atomic(work / "timing.rpt", sta.worst_path);
    fs::remove(work / "unit.v", ec);  // tens of megabytes; the script writes it again
    nlohmann::json result = {
        {"seconds", seconds},
        {"blocks", block_areas(unit, config, log_path, multiplies)},
        {"flop_table_lines", config.flop_lines},
        {"flop_table_area_um2",
         config.has_table ? table_area(parse_stat(read_text_file(work / "table.log"))) : 0.0},
        {"timing", block_timing(sta, (work / "unit.v").string())},
        {"flow", options.flow},
    };
    if (recover) result["recovery"] = recovery;
    if (const std::string wrong = check_synthesis(result); !wrong.empty())
      throw std::runtime_error(fmt::format("area: the synthesis makes no sense ({}); log {}", wrong,
                                           (work / "unit.log").string()));
    write_file_atomic(work / "result.json", result.dump(2) + "\n");
  });
  if (!synthesised) synthesised = read_json_file(config.dir / "result.json");
  AreaReport report = area_report(design, widths, config, *synthesised, options);
  report.cached = cached;
  return report;
}

nlohmann::json area_json(const AreaReport& r, const AreaOptions& options) {
  nlohmann::json widths;
  for (const auto& p : param_table()) widths[p.name] = r.widths.*(p.field);
  nlohmann::json blocks = nlohmann::json::array();
  for (const BlockArea& b : r.blocks)
    blocks.push_back({{"name", b.name}, {"area_um2", b.area_um2}, {"nand2_eq", b.nand2_eq},
                      {"flops", b.flops},
                      {"critical_path_ns", b.critical_path_ns < 0 ? nlohmann::json(nullptr) : nlohmann::json(b.critical_path_ns)},
                      {"widest_multiply", b.mul_product_bits < 0    ? nlohmann::json(nullptr)
                                          : b.mul_product_bits == 0 ? nlohmann::json::object()
                                                                    : nlohmann::json{{"a_bits", b.mul_a_bits},
                                                                                     {"b_bits", b.mul_b_bits},
                                                                                     {"product_bits", b.mul_product_bits}}}});
  return {{"design", r.design},
          {"widths", widths},
          {"blocks", blocks},
          {"logic_area_um2", r.logic_area_um2},
          {"sram_bits", r.sram_bits},
          {"sram_area_um2", r.sram_area_um2},
          {"sram_two_port", r.sram_two_port},
          {"sram_model",
           {{"bit_cell_um2", options.sram_cell_um2},
            {"array_efficiency", options.sram_efficiency},
            {"two_port_factor", options.sram_two_port_factor}}},
          {"flop_table_area_um2", r.flop_table_area_um2},
          {"flop_table_lines_synthesised", r.flop_table_lines_synthesised},
          {"total_area_um2", r.total_area_um2},
          {"critical_path_ns", r.critical_path_ns < 0 ? nlohmann::json(nullptr) : nlohmann::json(r.critical_path_ns)},
          {"table_critical_path_ns", r.table_path_ns < 0 ? nlohmann::json(nullptr) : nlohmann::json(r.table_path_ns)},
          {"fmax_mhz", r.critical_path_ns < 0 ? nlohmann::json(nullptr) : nlohmann::json(r.fmax_mhz)},
          {"critical_block", r.critical_path_ns < 0 ? nlohmann::json(nullptr) : nlohmann::json(critical_block(r))},
          {"critical_path", r.critical_path_ns < 0 ? nlohmann::json(nullptr)
                                                   : nlohmann::json{{"from", r.critical_path_from},
                                                                    {"to", r.critical_path_to},
                                                                    {"report", r.timing_report_path}}},
          {"flow", r.flow},
          {"recovery", r.flow != "recover" ? nlohmann::json(nullptr)
                                           : nlohmann::json{{"target_ns", r.recovery_target_ns},
                                                            {"area_mapped_modules", r.area_mapped_modules},
                                                            {"modules", r.modules},
                                                            {"delay_mapped_logic_um2", r.delay_mapped_logic_um2},
                                                            {"area_mapped_logic_um2", r.area_mapped_logic_um2}}},
          {"clock_target_mhz", options.clock_mhz > 0 ? nlohmann::json(options.clock_mhz) : nlohmann::json(nullptr)},
          {"synthesis_seconds", r.synthesis_seconds},
          {"estimated", r.estimated},
          {"liberty", options.liberty},
          {"build", kBuildRevision}};
}

double nand2_area_um2(const AreaOptions& options) {
  return liberty_cell_area(options.liberty, "NAND2X1");
}

std::string critical_block(const AreaReport& r) {
  if (r.critical_path_ns <= 0) return "";
  std::string block;
  double longest = -1;
  for (const BlockArea& b : r.blocks)
    if (b.critical_path_ns > longest) {
      longest = b.critical_path_ns;
      block = b.name;
    }
  return r.table_path_ns > longest ? "scanline table" : block;
}

nlohmann::json area_summary_json(const AreaReport& r, double px_per_clk) {
  double nand2_eq = 0;
  int64_t flops = 0;
  for (const BlockArea& b : r.blocks) {
    nand2_eq += b.nand2_eq;
    flops += b.flops;
  }
  nlohmann::json j = {{"logic_area_um2", r.logic_area_um2}, {"nand2_eq", nand2_eq}, {"flops", flops},
          {"sram_bits", r.sram_bits},           {"sram_two_port", r.sram_two_port},
          {"sram_area_um2", r.sram_area_um2},   {"flop_table_area_um2", r.flop_table_area_um2},
          {"total_area_um2", r.total_area_um2}};
  const bool timed = r.critical_path_ns > 0;
  j["critical_path_ns"] = timed ? nlohmann::json(r.critical_path_ns) : nlohmann::json(nullptr);
  j["fmax_mhz"] = timed ? nlohmann::json(r.fmax_mhz) : nlohmann::json(nullptr);
  j["critical_block"] = timed ? nlohmann::json(critical_block(r)) : nlohmann::json(nullptr);
  if (px_per_clk >= 0) {
    const double rate = px_per_clk * r.fmax_mhz;
    j["px_per_clk"] = px_per_clk;
    j["mpix_per_s"] = timed ? nlohmann::json(rate) : nlohmann::json(nullptr);
    j["um2_per_mpix_per_s"] = timed && rate > 0 ? nlohmann::json(r.total_area_um2 / rate) : nlohmann::json(nullptr);
  }
  return j;
}

std::string area_table(const std::vector<AreaReport>& reports, const AreaOptions& options,
                       const std::vector<double>& px_per_clk) {
  std::string out = fmt::format(
      "area: {} onto {} (NAND2X1 = {} um^2), SRAM at {} um^2 per bit / {} efficiency, x {:.3g} where "
      "two-port (2p: early_walk) (docs/area.md)\n",
      options.estimate ? "the component area model, calibrated by Yosys,"
                       : fmt::format("Yosys, flow {}", options.flow),
      fs::path(options.liberty).filename().string(), nand2_area_um2(options), options.sram_cell_um2,
      options.sram_efficiency, options.sram_two_port_factor);
  const bool rates = px_per_clk.size() == reports.size();
  out += fmt::format("{:<17} {:>13} {:>10} {:>8} {:>10} {:>12} {:>13} {:>9}", "design", "logic um^2",
                     "NAND2-eq", "flops", "SRAM bits", "SRAM um^2", "total um^2", "f_max MHz");
  out += rates ? fmt::format(" {:>7} {:>8} {:>13}\n", "px/clk", "Mpx/s", "um^2/(Mpx/s)") : "\n";
  for (size_t i = 0; i < reports.size(); ++i) {
    const AreaReport& r = reports[i];
    const nlohmann::json a = area_summary_json(r, rates ? px_per_clk[i] : -1);
    const auto number = [&](const char* key, const char* format) {
      return a.at(key).is_null() ? std::string("?") : fmt::format(fmt::runtime(format), a.at(key).get<double>());
    };
    out += fmt::format("{:<17} {:>13.0f} {:>10.0f} {:>8} {:>10} {:>12.0f} {:>13.0f} {:>9}", r.design,
                       r.logic_area_um2, a.at("nand2_eq").get<double>(), a.at("flops").get<int64_t>(),
                       fmt::format("{}{}", r.sram_bits, r.sram_two_port ? " 2p" : ""), r.sram_area_um2,
                       r.total_area_um2, number("fmax_mhz", "{:.1f}"));
    out += rates ? fmt::format(" {:>7.3f} {:>8} {:>13}\n", px_per_clk[i], number("mpix_per_s", "{:.1f}"),
                               number("um2_per_mpix_per_s", "{:.0f}"))
                 : "\n";
  }
  out += fmt::format("(f_max: OpenSTA on the synthesised netlist, ideal clock, no wires{}; docs/area.md)\n",
                     rates ? "; Mpx/s = px/clk on the scene x f_max" : "");
  return out;
}

std::vector<AreaReport> synthesise_areas(const std::vector<AreaJob>& list, const AreaOptions& options,
                                         unsigned threads) {
  // Distinct configurations, in first-seen order.
  std::map<std::string, size_t> index_of;
  std::vector<size_t> slot(list.size());
  std::vector<const AreaJob*> distinct;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string key = list[i].design.name + " " + describe(list[i].widths);
    const auto [it, added] = index_of.emplace(key, distinct.size());
    if (added) distinct.push_back(&list[i]);
    slot[i] = it->second;
  }
  AreaOptions quiet = options;
  quiet.quiet = true;
  std::vector<AreaReport> reports(distinct.size());
  run_parallel(distinct.size(), threads, "area",
               options.estimate ? "estimates (component model, cached)" : "syntheses (Yosys, cached)",
               [&](size_t i) { reports[i] = synthesise_area(distinct[i]->design, distinct[i]->widths, quiet); });
  std::vector<AreaReport> out;
  out.reserve(list.size());
  for (size_t i = 0; i < list.size(); ++i) out.push_back(reports[slot[i]]);
  return out;
}

CLI::Option* add_area_flow_option(CLI::App* cmd, std::string& flow, const std::string& name) {
  return cmd->add_option(name, flow,
                         "synthesis flow: delay, ABC at its delay corner everywhere; recover, each module also "
                         "mapped for area, and kept so where no path over the clock (cdsim area --clock-mhz, else "
                         "the delay flow's f_max) runs through it (docs/area.md)")
      ->check(CLI::IsMember({"delay", "recover"}))
      ->capture_default_str();
}

CLI::App* add_area_command(CLI::App& app, AreaOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "area", "synthesise the unit with Yosys onto osu018 cells: area per block, table as SRAM");
  cmd->add_option("--design", options.design, "design to synthesise (one with RTL: cdsim designs)")
      ->capture_default_str();
  cmd->add_option("--set", options.settings, "NAME=VALUE width or parameter (cdsim widths)");
  cmd->add_option("--json", options.json_path, "also write the report as JSON to this file");
  cmd->add_option("--cache", options.cache_dir,
                  "cache folder (default $XDG_CACHE_HOME/cdsim/area or ~/.cache/cdsim/area)");
  cmd->add_option("--liberty", options.liberty, "standard-cell liberty file")->capture_default_str();
  cmd->add_option("--clock-mhz", options.clock_mhz,
                  "map for this clock (ABC's delay target: faster gates where the period needs them, more area) "
                  "and say whether the timing meets it")
      ->check(CLI::Range(1.0, 2000.0));
  add_area_flow_option(cmd, options.flow, "--flow");
  cmd->add_flag("--model", options.estimate,
                "estimate by the component area model (an elaboration of about 5 s, no mapping) "
                "instead of synthesising; cdsim area-model calibrates it");
  cmd->add_option("--model-file", options.model_path, "the model's calibration (default: rtl/area_model.json)");
  cmd->add_option("--sram-cell-um2", options.sram_cell_um2, "SRAM bit-cell area (docs/area.md)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--sram-efficiency", options.sram_efficiency,
                  "SRAM array efficiency: bit cells / macro area (docs/area.md)")
      ->check(CLI::Range(0.05, 1.0))
      ->capture_default_str();
  cmd->add_option("--sram-two-port-factor", options.sram_two_port_factor,
                  "area of a two-port (read + write) bit cell over a single-port one, for early_walk (docs/area.md)")
      ->check(CLI::Range(1.0, 4.0))
      ->capture_default_str();
  return cmd;
}

int run_area_command(const AreaOptions& options) {
  if (!options.json_path.empty()) {
    check_output_folder("--json", options.json_path);
    check_distinct_files({{"--json", options.json_path}},
                         {{"--liberty", options.liberty}, {"--model-file", options.model_path}});
  }
  Widths widths;
  for (const std::string& s : options.settings) apply_setting(widths, s);
  const Design& design = find_design(options.design);
  const AreaReport r = synthesise_area(design, widths, options);
  fmt::print("area of {} at {}\n", r.design, describe(r.widths));
  fmt::print("build {}, liberty {}, flow {}, {}\n", kBuildRevision, options.liberty, r.estimated ? "-" : r.flow,
             r.estimated ? fmt::format("estimated by the component area model {} (docs/area.md; "
                                       "elaborated in {:.0f} s)", r.log_path, r.synthesis_seconds)
             : r.cached  ? fmt::format("cached (synthesised in {:.0f} s)", r.synthesis_seconds)
                         : fmt::format("synthesised in {:.0f} s", r.synthesis_seconds));
  fmt::print("\n{:<20} {:>14} {:>11} {:>8} {:>14} {:>8}\n", "block", "area um^2", "NAND2-eq", "flops",
             "widest mul", "path ns");
  const auto path_ns = [&](double ns) {
    return r.estimated ? std::string("?") : ns < 0 ? std::string("-") : fmt::format("{:.2f}", ns);
  };
  for (const BlockArea& b : r.blocks)
    fmt::print("{:<20} {:>14.0f} {:>11.0f} {:>8} {:>14} {:>8}\n", b.name, b.area_um2, b.nand2_eq, b.flops,
               b.mul_product_bits < 0    ? std::string("?")
               : b.mul_product_bits == 0 ? std::string("-")
                                         : fmt::format("{}x{}={}", b.mul_a_bits, b.mul_b_bits, b.mul_product_bits),
               path_ns(b.critical_path_ns));
  fmt::print("(widest mul: the block's multiply with the widest product, A x B = product bits, as Yosys sizes it before mapping;\n"
             " path ns: the shortest clock period that the worst path ending at the block's flip-flops meets, by OpenSTA)\n");
  fmt::print("{:<20} {:>14.0f}\n", "logic total", r.logic_area_um2);
  if (r.critical_path_ns > 0) {
    fmt::print("\nclock: critical path {:.2f} ns in the {}, f_max {:.1f} MHz (OpenSTA on the mapped netlist: ideal clock, "
               "no wires; docs/area.md)\n  from {}\n  to   {}\n  report {}\n",
               r.critical_path_ns, critical_block(r), r.fmax_mhz, r.critical_path_from, r.critical_path_to,
               r.timing_report_path);
    if (r.flow == "recover")
      fmt::print("  flow recover: {} of {} modules area-mapped, every path held to {:.2f} ns; logic {:.0f} um^2 "
                 "against {:.0f} all delay-mapped ({:+.1f}%) and {:.0f} all area-mapped\n",
                 r.area_mapped_modules, r.modules, r.recovery_target_ns, r.logic_area_um2, r.delay_mapped_logic_um2,
                 100 * (r.logic_area_um2 / r.delay_mapped_logic_um2 - 1), r.area_mapped_logic_um2);
    if (options.clock_mhz > 0)
      fmt::print("  mapped for {} MHz ({:.2f} ns): {} (slack {:+.2f} ns)\n", options.clock_mhz, 1000 / options.clock_mhz,
                 r.fmax_mhz >= options.clock_mhz ? "met" : "NOT met", 1000 / options.clock_mhz - r.critical_path_ns);
  }
  if (r.sram_bits == 0) {
    fmt::print("\nno scanline table\ntotal (logic): {:.0f} um^2\n", r.total_area_um2);
  } else {
    const int word_bits = unit_word_bits(derive(r.widths), find_design(r.design).persp);
    fmt::print("\nscanline table: {} bits ({} lines x {} bits, flags included)\n", r.sram_bits,
               r.sram_bits / word_bits, word_bits);
    fmt::print("  as SRAM:        {:>14.0f} um^2 ({} um^2 bit cell{} / {} array efficiency)\n",
               r.sram_area_um2, options.sram_cell_um2,
               r.sram_two_port ? fmt::format(" x {:.3g} two-port (early_walk)", options.sram_two_port_factor) : "",
               options.sram_efficiency);
    fmt::print("  as flip-flops:  {:>14.0f} um^2 (synthesised at {} lines{})\n", r.flop_table_area_um2,
               r.flop_table_lines_synthesised,
               r.flop_table_lines_synthesised * word_bits == r.sram_bits
                   ? ""
                   : ", scaled linearly to the full depth");
    if (r.table_path_ns > 0)
      fmt::print("  paths into it:  {:>11.2f} ns (OpenSTA, the table timed as flip-flops; docs/area.md)\n",
                 r.table_path_ns);
    fmt::print("total (logic + SRAM table): {:.0f} um^2\n", r.total_area_um2);
  }
  if (!options.json_path.empty()) {
    write_file_atomic(options.json_path, area_json(r, options).dump(2) + "\n");
    fmt::print("wrote {}\n", options.json_path);
  }
  return 0;
}

}  // namespace cdsim
