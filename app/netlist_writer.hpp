// The mapped netlist OpenSTA times, written from Yosys's JSON (write_json)
// rather than by Yosys's write_verilog: Yosys 0.23's write_verilog spends most
// of a synthesis's time escaping names (it rebuilds its keyword table for every
// identifier: Yosys issue #3845, fixed in 0.32), 56 s of 140 at narrow widths,
// where write_json takes about a second. Structural Verilog only: one module
// per Yosys module, scalar nets, named pin connections, assigns for output
// ports that are constants or other ports' nets.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace cdsim {

// Structural Verilog of every module of a Yosys JSON netlist (blackboxes left
// out). Private (hidden) cell and net names become _c<N>_ and _n<N>_; public
// ones keep their names, escaped where Verilog needs it. Throws
// std::runtime_error on a netlist it cannot write (a cell type still a Yosys
// internal cell, a bit of unknown kind).
std::string verilog_from_yosys_json(const nlohmann::json& netlist);

// The same, module by module (name as Yosys names it, then its Verilog), in
// the netlist's order; and the file written from such a list. cdsim area's
// recovering flow (app/area_recovery.hpp) takes each module from one of two
// mappings of the same netlist.
std::vector<std::pair<std::string, std::string>> verilog_modules_from_yosys_json(const nlohmann::json& netlist);
std::string verilog_from_modules(const std::vector<std::pair<std::string, std::string>>& modules);

// Reads `json_path` (write_json's output) and writes `verilog_path`.
void write_verilog_from_yosys_json(const std::filesystem::path& json_path,
                                   const std::filesystem::path& verilog_path);

}  // namespace cdsim
