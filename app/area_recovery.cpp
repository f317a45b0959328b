#include "area_recovery.hpp"

#include <fmt/format.h>

#include <map>
#include <stdexcept>

#include "cache_files.hpp"
#include "netlist_writer.hpp"

namespace cdsim {

namespace fs = std::filesystem;

namespace {

// A path more than this over the target (0.5%, and 1 ps for OpenSTA's
// rounding) is over it. Not zero: an area-mapped module loads the nets that
// enter it differently, so a path through delay-mapped modules alone can
// end a little over the all-delay netlist's (quad-sub8 at narrow widths:
// 28.48 ns against 28.35, +0.46%), and no move of the path's own modules
// cures that.
constexpr double kTolerance = 0.005;
double over(double target_ns) { return target_ns * (1 + kTolerance) + 0.001; }
// A round that moves modules to the delay mapping removes the paths through
// them; each round moves at least one, so this bounds a search that would
// otherwise end anyway, and keeps a pathological netlist from timing for hours.
constexpr int kMaxRounds = 16;

double critical_ns(const StaReport& sta, const fs::path& netlist) {
  if (sta.endpoints.empty())
    throw std::runtime_error(fmt::format("area: OpenSTA timed no flip-flop in {}", netlist.string()));
  return sta.endpoints.front().period_ns;
}

}  // namespace

std::string module_of_cell(const StaReport& sta, const std::string& cell, const std::string& top) {
  const size_t slash = cell.rfind('/');
  if (slash == std::string::npos) return top;
  const auto it = sta.instance_module.find(cell.substr(0, slash));
  if (it == sta.instance_module.end())
    throw std::runtime_error(fmt::format("area: OpenSTA names cell {}, whose instance it did not list", cell));
  return it->second;
}

Recovery recover_area(const ModuleTexts& delay, const ModuleTexts& area, double target_ns, const std::string& top,
                      const std::string& liberty, const std::string& clock, const fs::path& work,
                      const std::function<void(const std::string&)>& progress) {
  std::map<std::string, const std::string*> area_text;
  for (const auto& [name, text] : area) area_text[name] = &text;
  std::set<std::string> delay_names;
  for (const auto& [name, text] : delay) delay_names.insert(name);
  for (const auto& [name, text] : area)
    if (!delay_names.count(name))
      throw std::runtime_error(fmt::format("area: module {} is in the area mapping only", name));
  for (const std::string& name : delay_names)
    if (!area_text.count(name))
      throw std::runtime_error(fmt::format("area: module {} is in the delay mapping only", name));

  Recovery r;
  r.modules = delay.size();
  const fs::path netlist = work / "unit.v";
  // The netlist of the current choice, each module's text from its mapping.
  const auto write_choice = [&] {
    ModuleTexts chosen;
    for (const auto& [name, delay_text] : delay)
      chosen.emplace_back(name, r.area_modules.count(name) ? *area_text.at(name) : delay_text);
    write_file_atomic(netlist, verilog_from_modules(chosen));
  };
  const auto time_choice = [&](double over_ns) {
    write_choice();
    return time_netlist({netlist}, top, liberty, clock, work, over_ns, 200);
  };

  r.delay = time_choice(0);
  const double delay_ns = critical_ns(r.delay, netlist);
  r.target_ns = target_ns > 0 ? target_ns : delay_ns;
  for (const auto& [name, text] : delay) r.area_modules.insert(name);
  for (r.rounds = 1;; ++r.rounds) {
    r.chosen = time_choice(over(r.target_ns));
    const double worst = critical_ns(r.chosen, netlist);
    // The worst path that runs through an area-mapped module: its modules
    // go back to the delay mapping. One path a round, so that a module
    // that lies only on paths the first moves cure keeps its area mapping.
    size_t moved = 0;
    for (const auto& path : r.chosen.over_paths) {
      for (const auto& [cell, type] : path) moved += r.area_modules.erase(module_of_cell(r.chosen, cell, top));
      if (moved) break;
    }
    if (progress)
      progress(fmt::format("area recovery, round {}: worst path {:.2f} ns against {:.2f}; {} of {} modules "
                           "area-mapped{}", r.rounds, worst, r.target_ns, r.area_modules.size() + moved, r.modules,
                           moved ? fmt::format(", {} back to the delay mapping", moved) : ""));
    if (worst <= over(r.target_ns)) break;
    if (moved == 0 || r.rounds == kMaxRounds) {
      // What is left over the target is the delay mapping's own (a target
      // beyond the clock it reaches), or the search did not settle: unless
      // the mix is no slower than the all-delay netlist, take that.
      if (worst > over(delay_ns)) {
        r.area_modules.clear();
        r.fell_back = true;
        write_choice();
        r.chosen = r.delay;  // timed already
      }
      break;
    }
  }
  return r;
}

}  // namespace cdsim
