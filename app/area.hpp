// cdsim area: synthesises the scan unit's RTL at given widths with Yosys onto
// the osu018 standard cells (Debian's qflow-tech-osu018, 0.18 um) and reports
// the area per block, the scanline table as SRAM, and the same table built from
// flip-flops. Results are cached by a hash of the RTL sources, the design, the
// widths and the flow. docs/area.md describes the flow and its assumptions.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "design.hpp"
#include "widths.hpp"

namespace cdsim {

struct BlockArea {
  std::string name;
  double area_um2 = 0;
  double nand2_eq = 0;
  int64_t flops = 0;
  // The multiply of the block with the widest product (Yosys's $mul after
  // wreduce, before it is mapped; the larger A x B among equal products):
  // operand and product bits. All 0: no multiply; all -1: not known (the
  // component model's estimates).
  int mul_a_bits = -1, mul_b_bits = -1, mul_product_bits = -1;
  // The shortest clock period that the worst path ending at one of the
  // block's flip-flops meets (OpenSTA: clock to Q, logic, setup); -1 when no
  // path ends in the block (it has no flip-flop, or an estimate: not timed).
  double critical_path_ns = -1;
};

struct AreaReport {
  std::string design;
  Widths widths;
  std::vector<BlockArea> blocks;  // the blocks present in this design, then control
  double logic_area_um2 = 0;
  int64_t sram_bits = 0;
  bool sram_two_port = false;      // early_walk: a read and a write port
  double sram_area_um2 = 0;
  double flop_table_area_um2 = 0;  // the same table from flip-flops
  int64_t flop_table_lines_synthesised = 0;
  double total_area_um2 = 0;       // logic + SRAM
  double synthesis_seconds = 0;
  bool cached = false;
  bool estimated = false;          // by the component area model (area_model.hpp), not synthesis
  std::string log_path;
  // Static timing of the synthesised netlist (app/sta.hpp; not of estimates):
  // the unit's worst flip-flop to flip-flop path as a clock period, and the
  // clock it allows. -1 and 0 when not timed.
  double critical_path_ns = -1;
  double fmax_mhz = 0;
  std::string critical_path_from, critical_path_to;  // its start and end points
  std::string timing_report_path;                    // OpenSTA's report of that path
  double table_path_ns = -1;  // the worst path into the scanline table (its timing model); -1: none
  // The flow (AreaOptions::flow) and, for "recover", what it chose: the
  // period every path was held to, how many modules kept the area mapping,
  // and the logic area with every module delay-mapped (the delay flow's) and
  // with every module area-mapped.
  std::string flow = "delay";
  double recovery_target_ns = -1;
  size_t area_mapped_modules = 0, modules = 0;
  double delay_mapped_logic_um2 = -1, area_mapped_logic_um2 = -1;
};

struct AreaOptions {
  std::string design = "cd-linear";
  std::vector<std::string> settings;
  std::string json_path;
  std::string cache_dir;  // default: $XDG_CACHE_HOME/cdsim/area or ~/.cache/cdsim/area
  std::string liberty = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib";
  double sram_cell_um2 = 6.0;    // docs/area.md: 600 lambda^2, lambda = 0.10 um (osu018's SCMOS rules)
  double sram_efficiency = 0.65; // cell array / macro area
  // early_walk reads and writes the table in one cycle: a two-port (8T) bit
  // cell, this many times the 6T cell (docs/area.md).
  double sram_two_port_factor = 4.0 / 3.0;
  bool quiet = false;            // no "synthesising" line (batches show a progress bar instead)
  bool estimate = false;         // the component area model instead of synthesis (area_model.hpp)
  double clock_mhz = 0;          // > 0: map for this clock (ABC's delay target; docs/area.md, "Timing")
  std::string model_path;        // its calibration (default: rtl/area_model.json)
  // "delay": every module mapped at ABC's delay corner (docs/area.md, "The
  // flow"); "recover": each module also mapped at its area corner and kept so
  // where no path over the target runs through it (app/area_recovery.hpp).
  std::string flow = "delay";
};

// One configuration to synthesise.
struct AreaJob {
  Design design;
  Widths widths;
};

// Synthesises (or reads from the cache). Throws std::runtime_error with Yosys's
// own message and the log's path when synthesis fails or a check fails.
// With options.estimate, estimate_area (area_model.hpp) instead.
AreaReport synthesise_area(const Design& design, const Widths& widths, const AreaOptions& options);
nlohmann::json area_json(const AreaReport& report, const AreaOptions& options);

// Synthesises each distinct configuration of `list` once (the cache makes a
// repeated one free), `threads` Yosys runs at a time (0: all cores), with a
// progress bar on stderr. The reports come back in the order of `list`.
// Stops at the first failure, or on SIGINT/SIGTERM, and throws.
std::vector<AreaReport> synthesise_areas(const std::vector<AreaJob>& list,
                                         const AreaOptions& options, unsigned threads);

// The keys of the per-design area summary `run` and `sweep` print and write:
// logic um^2, NAND2-eq, SRAM bits, SRAM um^2, total um^2, the critical path
// and f_max (null for estimates); given the design's px/clk on the scene
// (>= 0), also px_per_clk, mpix_per_s (px/clk x f_max) and um2_per_mpix_per_s.
// The block whose worst path sets the unit's clock: the block of the longest
// block path, or "scanline table" when the paths into the table are longer;
// "" when the report is not timed.
std::string critical_block(const AreaReport& report);
nlohmann::json area_summary_json(const AreaReport& report, double px_per_clk = -1);
double nand2_area_um2(const AreaOptions& options);
// The readable table of those keys, one line per report, with the rates when
// px_per_clk holds one per report.
std::string area_table(const std::vector<AreaReport>& reports, const AreaOptions& options,
                       const std::vector<double>& px_per_clk = {});

CLI::App* add_area_command(CLI::App& app, AreaOptions& options);
// `name` (--flow, or --area-flow where the command has flows of its own):
// AreaOptions::flow, "delay" or "recover".
CLI::Option* add_area_flow_option(CLI::App* cmd, std::string& flow, const std::string& name = "--area-flow");
int run_area_command(const AreaOptions& options);

}  // namespace cdsim
