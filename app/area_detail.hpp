// The parts of cdsim area's synthesis flow that the component area model
// (area_model.cpp) shares: the unit's configuration and Yosys front end, the
// statistics parser and the attribution of modules to blocks.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "area.hpp"

namespace cdsim::area_detail {

// One module of `stat -liberty` output (or of the model's prediction): its own
// cell area, own flip-flops, and how many instances of each submodule it holds.
struct ModuleStat {
  double own_area = 0;
  int64_t own_flops = 0;
  std::map<std::string, int64_t> cells;       // cell type -> count
  std::map<std::string, int64_t> submodules;  // the cells that are modules
};

// One design at one set of widths, as Yosys is given it.
struct UnitConfig {
  std::filesystem::path dir;      // its cache folder (hash of RTL, widths, design and flow)
  std::string top;                // cd_scan_unit, or adaptive_unit (model/design.hpp, RtlTop)
  std::string header;             // cd_widths.svh
  std::string unit_front;         // read, chparam and hierarchy of the unit (table a black box)
  std::string table_front;        // the same for the flip-flop table
  std::string reciprocal_owner;   // the module whose reciprocal is reported apart ("": none)
  bool has_table = false;
  int64_t sram_depth = 0;         // table lines, density included
  int64_t flop_lines = 0;         // lines of the synthesised flip-flop table (0: no table)
  int word_bits = 0;
};

// The RTL sources of a top ("cd_scan_unit" or "adaptive_unit"), as the
// simulations verilate them (named in cmake/rtl_sources.cmake), in name order.
std::vector<std::filesystem::path> rtl_sources_of(const std::string& top);
UnitConfig prepare_unit(const Design& design, const Widths& widths, const AreaOptions& options);
std::map<std::string, ModuleStat> parse_stat(const std::string& log);
// "$paramod$0123\shift_round" -> "shift_round".
std::string base_name(const std::string& module);
// The per-block areas and flip-flops of a unit's statistics (JSON as cached).
nlohmann::json block_areas(const std::map<std::string, ModuleStat>& unit, const UnitConfig& config,
                           const std::string& log_path);
double table_area(const std::map<std::string, ModuleStat>& table);
// The report from cached block areas: SRAM, flop table scaled to full depth, totals.
AreaReport area_report(const Design& design, const Widths& widths, const UnitConfig& config,
                       const nlohmann::json& synthesised, const AreaOptions& options);
int run_yosys(const std::filesystem::path& script, const std::filesystem::path& log);
std::string yosys_error(const std::filesystem::path& log);

}  // namespace cdsim::area_detail
