// Static timing of a mapped netlist with OpenSTA (Debian's `opensta`, command
// `sta`): the netlist cdsim area writes after mapping onto the liberty's
// cells, timed against the same liberty with an ideal clock on one port.
// docs/area.md, "Timing", states what it models and what it does not (no
// wires, no placement, no clock tree).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace cdsim {

// The worst register-to-register path that ends at one flip-flop's data pin.
struct StaEndpoint {
  std::string pin;            // hierarchical, '/'-separated: "u_setup_engine/_5807_/D"
  double period_ns = 0;       // the shortest clock period that path meets: arrival + setup
};

struct StaReport {
  // The netlist's hierarchical instances (full name -> module), leaf cells left out.
  std::map<std::string, std::string> instance_module;
  std::vector<StaEndpoint> endpoints;  // every flip-flop data pin a path reaches, worst first
  std::string worst_from, worst_to;    // the worst path's start and end points ("" when none)
  std::string worst_path;              // OpenSTA's report of that path
  // With time_netlist's `over_ns`: the worst path into each endpoint whose
  // period is over it, worst first, each as its logic cells (flip-flops left
  // out): (hierarchical cell name, cell type), ("u_setup_engine/_5807_", "OAI21X1").
  std::vector<std::vector<std::pair<std::string, std::string>>> over_paths;
  double seconds = 0;
};

// Times `netlists` (structural Verilog of the liberty's cells, as Yosys's
// write_verilog -noattr -noexpr, or app/netlist_writer.cpp, gives it; the first is named in errors) with
// `top` as the design and an ideal clock on port `clock`. A cell that none
// defines is an error, not a black box. Inputs and outputs carry no delay, so only
// paths from a flip-flop to a flip-flop are timed. Writes sta.tcl and sta.log
// into `work`. Throws std::runtime_error naming the log when OpenSTA fails or
// reports an error. With `over_ns` > 0 it also lists the cells on the paths
// over that period (the `max_paths` worst endpoints' paths at most).
StaReport time_netlist(const std::vector<std::filesystem::path>& netlists, const std::string& top,
                       const std::string& liberty, const std::string& clock, const std::filesystem::path& work,
                       double over_ns = 0, int max_paths = 2000);

// Parses sta.log as time_netlist's script writes it (exposed for tests).
StaReport parse_sta_log(const std::string& log, double clock_period_ns);

}  // namespace cdsim
