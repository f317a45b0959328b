// The parts of cdsim area's synthesis flow that the component area model
// (area_model.cpp) shares: the unit's configuration and Yosys front end, the
// statistics parser and the attribution of modules to blocks.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "area.hpp"
#include "cache_files.hpp"

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
  std::filesystem::path dir;      // its cache entry (hash of RTL, widths, design and flow)
  std::string top;                // cd_scan_unit, or adaptive_unit (model/design.hpp, RtlTop)
  std::string header;             // cd_widths.svh
  std::string unit_sources;       // the unit's RTL files but the table, space-separated
  std::string parameters;         // chparam's -set options
  std::string reciprocal_owner;   // the module whose reciprocal is reported apart ("": none)
  bool has_table = false;
  int64_t sram_depth = 0;         // table lines, density included
  int64_t bank_depth = 0;         // lines of one bank (scanline_table's Depth)
  int64_t flop_lines = 0;         // lines of the synthesised flip-flop table (0: no table)
  int word_bits = 0;

  // Yosys's read, chparam and hierarchy of the unit (the table a black box),
  // and of the flip-flop table, with cd_widths.svh taken from `include`: the
  // work folder that builds a result of the entry.
  std::string unit_front(const std::filesystem::path& include) const;
  std::string table_front(const std::filesystem::path& include) const;
};

// A cache entry's results (result.json, inventory.json), built under the
// entry's lock (<cache>/<hash>.lock: another cdsim waits instead of building
// it twice) and checked before use.
class EntryLock {
 public:
  EntryLock(const UnitConfig& config, const std::string& what);

 private:
  CacheEntryLock lock_;
};
// The result `name` of the entry, if its manifest vouches for it and `check`
// finds nothing wrong ("" = fine). Otherwise, when the file is there, says on
// stderr that it is corrupt, naming the file and what is wrong, removes it,
// and returns nothing, as for a result not yet built.
std::optional<nlohmann::json> cached_result(const UnitConfig& config, const std::string& name,
                                            const std::function<std::string(const nlohmann::json&)>& check);
// Builds the result `name` in a work folder of its own (<cache>/tmp-<hash>-*)
// that holds cd_widths.svh: build(work) writes name there, with its scripts
// and logs. Then they move into the entry, the result last, with its
// manifest. A failure or an interrupt removes the work folder; a failure keeps
// the logs in <cache>/failed-<hash>/ and names them.
void build_result(const UnitConfig& config, const std::string& name,
                  const std::function<void(const std::filesystem::path& work)>& build);
// "" when a cached synthesis (result.json) makes sense: finite areas and
// seconds, no negative area or count.
std::string check_synthesis(const nlohmann::json& synthesised);

// The RTL sources of a top ("cd_scan_unit" or "adaptive_unit"), as the
// simulations verilate them (named in cmake/rtl_sources.cmake), in name order.
std::vector<std::filesystem::path> rtl_sources_of(const std::string& top);
UnitConfig prepare_unit(const Design& design, const Widths& widths, const AreaOptions& options);
std::map<std::string, ModuleStat> parse_stat(const std::string& log);
// "$paramod$0123\shift_round" -> "shift_round".
std::string base_name(const std::string& module);
// A multiply's operand and product bits.
struct Multiply {
  int a = 0, b = 0, product = 0;
  bool wider_than(const Multiply& o) const {
    return product != o.product ? product > o.product : int64_t{a} * b > int64_t{o.a} * o.b;
  }
};
// Each module's widest multiply, from Yosys's `dump t:$mul` (RTLIL text).
std::map<std::string, Multiply> parse_multiplies(const std::string& dump);
// The per-block areas and flip-flops of a unit's statistics (JSON as cached),
// and each block's widest multiply from `multiplies` (by module, as
// parse_multiplies gives them).
nlohmann::json block_areas(const std::map<std::string, ModuleStat>& unit, const UnitConfig& config,
                           const std::string& log_path, const std::map<std::string, Multiply>& multiplies);
double table_area(const std::map<std::string, ModuleStat>& table);
// The block a module's instances are counted in ("column_walker" -> "column
// walker"; "" for none).
std::string block_of_module(const std::string& base);
// The block of a flip-flop pin of the timed netlist ("u_walker/_12_/D"), by
// the modules of the instances that hold it, as block_areas counts cells.
std::string block_of_pin(const std::map<std::string, std::string>& instance_module, const std::string& pin);
// The report from cached block areas: SRAM, flop table scaled to full depth, totals.
AreaReport area_report(const Design& design, const Widths& widths, const UnitConfig& config,
                       const nlohmann::json& synthesised, const AreaOptions& options);
// Runs Yosys on each script at once (-q -l log -s script), each in a process
// group of its own (support/child_process.hpp); SIGINT or SIGTERM stops them
// and throws Interrupted. Throws "yosys failed WHAT: ERROR (LOG)" for the
// first that fails.
struct YosysRun {
  std::filesystem::path script, log;
  std::string what;  // "on the unit"
};
void run_yosys(const std::vector<YosysRun>& runs);
// ABC's scripts (and abc.constr) in `work`: abc.script, the delay corner
// every flow maps with (aiming at `clock_mhz` when > 0), and
// abc_area.script, the area corner of the recovering flow.
void write_abc_script(const std::filesystem::path& work, double clock_mhz);
void write_area_abc_script(const std::filesystem::path& work);
std::string yosys_error(const std::filesystem::path& log);

}  // namespace cdsim::area_detail
