#include "area.hpp"

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

#include "build_info.hpp"
#include "cache_files.hpp"
#include "derived_widths.hpp"
#include "interrupt.hpp"
#include "progress.hpp"

namespace cdsim {

namespace fs = std::filesystem;

namespace {

// Bumped whenever the flow below changes, so that cached results are redone.
constexpr const char* kFlowVersion = "area-flow-4";

int log2_of(int value) {
  int bits = 0;
  while ((1 << bits) < value) ++bits;
  return bits;
}

// One module of `stat -liberty` output: its own cell area, own flip-flops, and
// how many instances of each submodule it holds.
struct ModuleStat {
  double own_area = 0;
  int64_t own_flops = 0;
  std::map<std::string, int64_t> cells;       // cell type -> count
  std::map<std::string, int64_t> submodules;  // the cells that are modules
};

// Yosys writes "=== cd_scan_unit ===" but "Chip area for module '\cd_scan_unit'".
std::string strip_escape(const std::string& name) {
  return !name.empty() && name[0] == '\\' ? name.substr(1) : name;
}

// "$paramod$0123\shift_round", "$paramod\setup_engine\SramDepth=..." and
// "\column_walker" all name a module by the part after the first backslash.
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

int run_yosys(const fs::path& script, const fs::path& log) {
  const std::string command =
      fmt::format("yosys -q -l '{}' -s '{}' > /dev/null 2>&1", log.string(), script.string());
  return std::system(command.c_str());
}

std::string yosys_error(const fs::path& log) {
  std::ifstream in(log);
  std::string line, error;
  while (std::getline(in, line))
    if (line.find("ERROR") != std::string::npos || line.find("Assertion failed") != std::string::npos)
      error = line;
  return error.empty() ? "see the log" : error;
}

}  // namespace

AreaReport synthesise_area(const Design& design, const Widths& widths, const AreaOptions& options) {
  if (!has_rtl(design))
    throw std::invalid_argument(fmt::format(
        "design '{}' has no RTL yet; cdsim area synthesises {}", design.name, rtl_design_names()));
  validate(widths);
  if (!fs::exists(options.liberty))
    throw std::runtime_error(fmt::format(
        "{}: no such liberty file (scripts/setup installs qflow-tech-osu018)", options.liberty));
  const DerivedWidths derived = derive(widths);
  // The unit elaborated with this design's hardware only (rtl/cd_scan_unit.sv).
  const bool has_table = design.kind == Design::Kind::ConstantDepth;
  const bool has_divide = design.kind == Design::Kind::Divide;
  const bool has_affine = design.kind == Design::Kind::Affine && design.subdivision == 0;
  const bool has_affine_sub = design.kind == Design::Kind::Affine && design.subdivision != 0;
  const bool has_kim_iter = design.kind == Design::Kind::Kim && !design.pipelined;
  const bool has_kim_pipe = design.kind == Design::Kind::Kim && design.pipelined;
  const int segment_log2 = has_affine_sub ? log2_of(design.subdivision) : 4;
  const int density_log2 = log2_of(design.density);
  const int has_correction = design.correction ? 1 : 0;
  const std::string parameters = fmt::format(
      "-set MaxDensityLog2 {} -set HasCorrection {} -set HasTable {:d} -set HasDivide {:d} "
      "-set HasAffine {:d} -set HasAffineSub {:d} -set MaxSegmentLog2 {} -set HasKimIter {:d} "
      "-set HasKimPipe {:d} -set HasObservation 0",
      density_log2, has_correction, has_table, has_divide, has_affine, has_affine_sub, segment_log2,
      has_kim_iter, has_kim_pipe);

  // Every RTL source, in name order, so that the hash is stable.
  const fs::path rtl_dir = kRtlDir;
  std::vector<fs::path> sources;
  for (const auto& entry : fs::directory_iterator(rtl_dir))
    if (entry.path().extension() == ".sv") sources.push_back(entry.path());
  std::sort(sources.begin(), sources.end());
  const std::string header = rtl_header(widths, "area");
  uint64_t hash = fnv1a(kFlowVersion);
  hash = fnv1a(header, hash);
  hash = fnv1a(fmt::format("{} {}", parameters, options.liberty), hash);
  for (const fs::path& source : sources) hash = fnv1a(read_text_file(source), hash);

  const fs::path cache = options.cache_dir.empty() ? cache_root("area") : fs::path(options.cache_dir);
  const fs::path dir = cache / fmt::format("{:016x}", hash);
  fs::create_directories(dir);
  const fs::path result_path = dir / "result.json";

  AreaReport report;
  report.design = design.name;
  report.widths = widths;
  report.log_path = (dir / "unit.log").string();
  const int64_t sram_depth = has_table ? int64_t{widths.table_depth} << density_log2 : 0;
  report.sram_bits = sram_depth * derived.word_bits;
  report.sram_area_um2 =
      static_cast<double>(report.sram_bits) * options.sram_cell_um2 / options.sram_efficiency;
  const double nand2 = liberty_cell_area(options.liberty, "NAND2X1");

  nlohmann::json synthesised;
  if (fs::exists(result_path)) {
    synthesised = nlohmann::json::parse(read_text_file(result_path));
    report.cached = true;
  } else {
    write_file_atomic(dir / "cd_widths.svh", header);
    std::string unit_sources;
    for (const fs::path& source : sources)
      if (source.filename() != "scanline_table.sv") unit_sources += " " + source.string();
    const std::string L = options.liberty;
    const std::string include = fmt::format("-I{} -I{}", dir.string(), rtl_dir.string());
    // The unit, with the scanline table as a black box (it is SRAM).
    write_file_atomic(dir / "unit.ys", fmt::format(
        "read_verilog -sv -DSYNTHESIS {inc}{src}\n"
        "read_verilog -sv -lib {inc} {rtl}/scanline_table.sv\n"
        "chparam {p} cd_scan_unit\n"
        "hierarchy -check -top cd_scan_unit\n"
        "proc\n"
        "select -assert-none t:$dlatch t:$adlatch t:$dlatchsr t:$sr\n"
        "opt -fast\n"
        "select -assert-none t:$div t:$mod t:$divfloor t:$modfloor\n"
        "wreduce\nalumacc\nopt -fast\nmemory -nomap\ntechmap\n"
        "dfflibmap -liberty {L}\nabc -fast -liberty {L}\nopt_clean\n"
        "select -assert-none t:$* t:$paramod* %d\n"
        "stat -liberty {L}\n",
        fmt::arg("inc", include), fmt::arg("src", unit_sources), fmt::arg("rtl", rtl_dir.string()),
        fmt::arg("p", parameters), fmt::arg("L", L)));
    // The same table from flip-flops, synthesised at up to 64 lines.
    const int64_t flop_lines = std::min<int64_t>(sram_depth, 64);  // 0: no table
    write_file_atomic(dir / "table.ys", fmt::format(
        "read_verilog -sv {inc} {rtl}/scanline_table.sv\n"
        "chparam -set Depth {d} -set WordBits {w} scanline_table\n"
        "hierarchy -check -top scanline_table\n"
        "proc\nopt -fast\nmemory\nopt -fast\ntechmap\n"
        "dfflibmap -liberty {L}\nabc -fast -liberty {L}\nopt_clean\n"
        "select -assert-none t:$* t:$paramod* %d\n"
        "stat -liberty {L}\n",
        fmt::arg("inc", include), fmt::arg("rtl", rtl_dir.string()), fmt::arg("d", flop_lines),
        fmt::arg("w", derived.word_bits), fmt::arg("L", L)));

    if (!options.quiet)
      std::cerr << fmt::format("area: synthesising {} with yosys onto {} (log {})\n", design.name,
                               fs::path(L).filename().string(), report.log_path);
    const auto start = std::chrono::steady_clock::now();
    int unit_status = 0, table_status = 0;
    std::thread table([&] {
      if (has_table) table_status = run_yosys(dir / "table.ys", dir / "table.log");
    });
    unit_status = run_yosys(dir / "unit.ys", dir / "unit.log");
    table.join();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (unit_status != 0)
      throw std::runtime_error(fmt::format("yosys failed on the unit: {} ({})",
                                           yosys_error(dir / "unit.log"), report.log_path));
    if (table_status != 0)
      throw std::runtime_error(fmt::format("yosys failed on the flip-flop table: {} ({})",
                                           yosys_error(dir / "table.log"), (dir / "table.log").string()));

    const auto unit = parse_stat(read_text_file(dir / "unit.log"));
    // Blocks: the top's submodules by kind (the table is a black box), each
    // reciprocal counted apart from the block that holds it, and the top's
    // own cells as control. They sum to the unit's logic.
    const std::string top = find_module(unit, "cd_scan_unit");
    const Subtree recip = subtree_of(unit, "reciprocal");  // one per design: fill or pixels
    static const std::map<std::string, std::string> block_of = {
        {"setup_engine", "setup engine"},     {"column_walker", "column walker"},
        {"correction_adder", "correction adder"}, {"plane_accumulator", "plane accumulators"},
        {"pixel_divide", "pixel multiply"},   {"affine_setup", "affine setup"},
        {"shift_round", "output rounding"},   {"affine_sub_datapath", "subdivision datapath"},
        {"kim_datapath", "Kim datapath"}};
    std::vector<std::string> order;
    std::map<std::string, Subtree> totals;
    const auto add = [&](const std::string& name, double area, int64_t flops) {
      if (!totals.count(name)) order.push_back(name);
      totals[name].area += area;
      totals[name].flops += flops;
    };
    for (const auto& [sub, count] : unit.at(top).submodules) {
      const std::string base = base_name(sub);
      if (base == "scanline_table") continue;
      const auto it = block_of.find(base);
      if (it == block_of.end())
        throw std::runtime_error(fmt::format("area: no block for module '{}' in {}", base, report.log_path));
      Subtree t = subtree(unit, sub);
      // The reciprocal, reported on its own, is the fill's (in the setup engine)
      // in the table designs, the pixels' (in pixel_divide) in divide and the
      // end points' in affine-subN.
      if ((base == "setup_engine" && has_table) || base == "pixel_divide" ||
          base == "affine_sub_datapath") {
        t.area -= recip.area;
        t.flops -= recip.flops;
      }
      add(it->second, static_cast<double>(count) * t.area, count * t.flops);
    }
    if (recip.area > 0) add("reciprocal", recip.area, recip.flops);
    const auto& control = unit.at(top);
    add("control", control.own_area, control.own_flops);
    nlohmann::json blocks = nlohmann::json::array();
    for (const std::string& name : order)
      blocks.push_back({{"name", name}, {"area_um2", totals[name].area}, {"flops", totals[name].flops}});
    double table_area = 0;
    if (has_table) {
      const auto flop_table = parse_stat(read_text_file(dir / "table.log"));
      table_area = subtree(flop_table, find_module(flop_table, "scanline_table")).area;
    }
    synthesised = {
        {"seconds", seconds},
        {"blocks", blocks},
        {"flop_table_lines", flop_lines},
        {"flop_table_area_um2", table_area},
    };
    write_file_atomic(result_path, synthesised.dump(2) + "\n");
  }
  report.synthesis_seconds = synthesised.at("seconds").get<double>();
  for (const auto& b : synthesised.at("blocks")) {
    if (b.at("area_um2").get<double>() == 0 && b.at("flops").get<int64_t>() == 0) continue;  // absent
    BlockArea block;
    block.name = b.at("name").get<std::string>();
    block.area_um2 = b.at("area_um2").get<double>();
    block.flops = b.at("flops").get<int64_t>();
    block.nand2_eq = block.area_um2 / nand2;
    report.logic_area_um2 += block.area_um2;
    report.blocks.push_back(block);
  }
  report.flop_table_lines_synthesised = synthesised.at("flop_table_lines").get<int64_t>();
  if (report.flop_table_lines_synthesised > 0)
    report.flop_table_area_um2 = synthesised.at("flop_table_area_um2").get<double>() *
                                 static_cast<double>(sram_depth) /
                                 static_cast<double>(report.flop_table_lines_synthesised);
  report.total_area_um2 = report.logic_area_um2 + report.sram_area_um2;
  return report;
}

nlohmann::json area_json(const AreaReport& r, const AreaOptions& options) {
  nlohmann::json widths;
  for (const auto& p : param_table()) widths[p.name] = r.widths.*(p.field);
  nlohmann::json blocks = nlohmann::json::array();
  for (const BlockArea& b : r.blocks)
    blocks.push_back({{"name", b.name}, {"area_um2", b.area_um2}, {"nand2_eq", b.nand2_eq},
                      {"flops", b.flops}});
  return {{"design", r.design},
          {"widths", widths},
          {"blocks", blocks},
          {"logic_area_um2", r.logic_area_um2},
          {"sram_bits", r.sram_bits},
          {"sram_area_um2", r.sram_area_um2},
          {"sram_model", {{"bit_cell_um2", options.sram_cell_um2}, {"array_efficiency", options.sram_efficiency}}},
          {"flop_table_area_um2", r.flop_table_area_um2},
          {"flop_table_lines_synthesised", r.flop_table_lines_synthesised},
          {"total_area_um2", r.total_area_um2},
          {"synthesis_seconds", r.synthesis_seconds},
          {"liberty", options.liberty},
          {"build", kBuildRevision}};
}

double nand2_area_um2(const AreaOptions& options) {
  return liberty_cell_area(options.liberty, "NAND2X1");
}

nlohmann::json area_summary_json(const AreaReport& r) {
  double nand2_eq = 0;
  for (const BlockArea& b : r.blocks) nand2_eq += b.nand2_eq;
  return {{"logic_area_um2", r.logic_area_um2}, {"nand2_eq", nand2_eq},
          {"sram_bits", r.sram_bits},           {"sram_area_um2", r.sram_area_um2},
          {"flop_table_area_um2", r.flop_table_area_um2}, {"total_area_um2", r.total_area_um2}};
}

std::string area_table(const std::vector<AreaReport>& reports, const AreaOptions& options) {
  std::string out = fmt::format(
      "area: Yosys onto {} (NAND2X1 = {} um^2), SRAM at {} um^2 per bit / {} efficiency (docs/area.md)\n",
      fs::path(options.liberty).filename().string(), nand2_area_um2(options), options.sram_cell_um2,
      options.sram_efficiency);
  out += fmt::format("{:<17} {:>13} {:>10} {:>10} {:>12} {:>13}\n", "design", "logic um^2", "NAND2-eq",
                     "SRAM bits", "SRAM um^2", "total um^2");
  for (const AreaReport& r : reports) {
    const nlohmann::json a = area_summary_json(r);
    out += fmt::format("{:<17} {:>13.0f} {:>10.0f} {:>10} {:>12.0f} {:>13.0f}\n", r.design,
                       r.logic_area_um2, a.at("nand2_eq").get<double>(), r.sram_bits, r.sram_area_um2,
                       r.total_area_um2);
  }
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
  const unsigned workers_wanted =
      threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  std::vector<AreaReport> reports(distinct.size());
  std::atomic<size_t> next{0}, done{0};
  std::atomic<unsigned> running{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const unsigned workers_count = std::min<unsigned>(workers_wanted, unsigned(distinct.size()));
  running = workers_count;
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < workers_count; ++t)
    workers.emplace_back([&] {
      for (size_t i; (i = next++) < distinct.size();) {
        try {
          reports[i] = synthesise_area(distinct[i]->design, distinct[i]->widths, quiet);
        } catch (...) {
          std::lock_guard<std::mutex> guard(failure_mutex);
          if (!failure) failure = std::current_exception();
          next = distinct.size();
        }
        ++done;
      }
      --running;
    });
  Progress progress(distinct.size(), "area", "syntheses (Yosys, cached)");
  bool shown = false;
  for (int tick = 0; running > 0; ++tick) {
    if (interrupted()) next = distinct.size();
    // Only a batch that really synthesises shows progress; a cached one is instant.
    if (tick >= 10 && tick % 10 == 0) {
      progress.update(done, elapsed());
      shown = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (auto& w : workers) w.join();
  throw_if_interrupted();
  if (failure) std::rethrow_exception(failure);
  if (shown) progress.update(done, elapsed(), true);
  std::vector<AreaReport> out;
  out.reserve(list.size());
  for (size_t i = 0; i < list.size(); ++i) out.push_back(reports[slot[i]]);
  return out;
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
  cmd->add_option("--sram-cell-um2", options.sram_cell_um2, "SRAM bit-cell area (docs/area.md)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--sram-efficiency", options.sram_efficiency,
                  "SRAM array efficiency: bit cells / macro area (docs/area.md)")
      ->check(CLI::Range(0.05, 1.0))
      ->capture_default_str();
  return cmd;
}

int run_area_command(const AreaOptions& options) {
  Widths widths;
  for (const std::string& s : options.settings) apply_setting(widths, s);
  const Design& design = find_design(options.design);
  const AreaReport r = synthesise_area(design, widths, options);
  fmt::print("area of {} at {}\n", r.design, describe(r.widths));
  fmt::print("build {}, liberty {}, {}\n", kBuildRevision, options.liberty,
             r.cached ? fmt::format("cached (synthesised in {:.0f} s)", r.synthesis_seconds)
                      : fmt::format("synthesised in {:.0f} s", r.synthesis_seconds));
  fmt::print("\n{:<18} {:>14} {:>11} {:>8}\n", "block", "area um^2", "NAND2-eq", "flops");
  for (const BlockArea& b : r.blocks)
    fmt::print("{:<18} {:>14.0f} {:>11.0f} {:>8}\n", b.name, b.area_um2, b.nand2_eq, b.flops);
  fmt::print("{:<18} {:>14.0f}\n", "logic total", r.logic_area_um2);
  if (r.sram_bits == 0) {
    fmt::print("\nno scanline table\ntotal (logic): {:.0f} um^2\n", r.total_area_um2);
  } else {
    fmt::print("\nscanline table: {} bits ({} lines x {} bits, flags included)\n", r.sram_bits,
               r.sram_bits / derive(r.widths).word_bits, derive(r.widths).word_bits);
    fmt::print("  as SRAM:        {:>14.0f} um^2 ({} um^2 bit cell / {} array efficiency)\n",
               r.sram_area_um2, options.sram_cell_um2, options.sram_efficiency);
    fmt::print("  as flip-flops:  {:>14.0f} um^2 (synthesised at {} lines{})\n", r.flop_table_area_um2,
               r.flop_table_lines_synthesised,
               r.flop_table_lines_synthesised * derive(r.widths).word_bits == r.sram_bits
                   ? ""
                   : ", scaled linearly to the full depth");
    fmt::print("total (logic + SRAM table): {:.0f} um^2\n", r.total_area_um2);
  }
  if (!options.json_path.empty()) {
    write_file_atomic(options.json_path, area_json(r, options).dump(2) + "\n");
    fmt::print("wrote {}\n", options.json_path);
  }
  return 0;
}

}  // namespace cdsim
