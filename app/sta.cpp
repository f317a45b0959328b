#include "sta.hpp"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "cache_files.hpp"
#include "child_process.hpp"
#include "interrupt.hpp"
#include "common.hpp"

namespace cdsim {

namespace fs = std::filesystem;

namespace {

// Any period does: the clock is ideal, so an endpoint's arrival and setup do
// not depend on it, and its shortest period is this period less its slack.
constexpr double kClockPeriodNs = 10.0;

// Lines the script prints around OpenSTA's reports, for the parser.
constexpr const char* kInstance = "cdsim-instance ";
constexpr const char* kEndpoints = "cdsim-endpoints";
constexpr const char* kWorst = "cdsim-worst";
constexpr const char* kOver = "cdsim-over";
constexpr const char* kEnd = "cdsim-end";

}  // namespace

StaReport parse_sta_log(const std::string& log, double clock_period_ns) {
  StaReport report;
  std::istringstream in(log);
  std::string line;
  enum class Section { Head, Endpoints, Worst, Over, Tail } section = Section::Head;
  // "u_a/_12_/D (DFFPOSX1)    9.8380   17.8720   -8.0340 (VIOLATED)", or (MET)
  static const std::regex endpoint(R"(^(\S+) \(\S+\)\s+(-?[0-9.]+)\s+(-?[0-9.]+)\s+(-?[0-9.]+)( \((VIOLATED|MET)\))?\s*$)");
  static const std::regex start(R"(^Startpoint: (\S+))");
  static const std::regex end(R"(^Endpoint: (\S+))");
  // A cell's output on a path: "   0.117    1.710 v u_a/_08556_/Y (OAI21X1)"
  static const std::regex path_pin(R"(^\s+-?[0-9.]+\s+-?[0-9.]+ [\^v] (\S+)/[^/\s]+ \((\S+)\)\s*$)");
  std::smatch m;
  while (std::getline(in, line)) {
    if (line.rfind("Error", 0) == 0) throw std::runtime_error(line);
    // A cell that is in neither the liberty nor the netlists: its paths would
    // go untimed.
    if (line.find("Creating black box") != std::string::npos) throw std::runtime_error(line);
    if (line.rfind(kInstance, 0) == 0) {
      std::istringstream fields(line.substr(std::string(kInstance).size()));
      std::string name, module;
      if (!(fields >> name >> module)) throw std::runtime_error("a malformed instance line: " + line);
      // OpenSTA doubles the backslashes of Yosys's names: $paramod\\setup_engine.
      for (size_t at = 0; (at = module.find("\\\\", at)) != std::string::npos; ++at) module.erase(at, 1);
      report.instance_module[name] = module;
    } else if (line == kEndpoints) {
      section = Section::Endpoints;
    } else if (line == kWorst) {
      section = Section::Worst;
    } else if (line == kOver) {
      section = Section::Over;
    } else if (line == kEnd) {
      section = Section::Tail;
    } else if (section == Section::Endpoints && std::regex_match(line, m, endpoint)) {
      report.endpoints.push_back({m[1], clock_period_ns - std::stod(m[4])});
    } else if (section == Section::Worst) {
      if (std::regex_search(line, m, start) && report.worst_from.empty()) report.worst_from = m[1];
      if (std::regex_search(line, m, end) && report.worst_to.empty()) report.worst_to = m[1];
      report.worst_path += line + "\n";
    } else if (section == Section::Over && std::regex_search(line, m, start)) {
      report.over_paths.emplace_back();
    } else if (section == Section::Over && std::regex_match(line, m, path_pin) && !report.over_paths.empty()) {
      const std::string type = m[2];
      if (type.rfind("DFF", 0) != 0 && type.rfind("LATCH", 0) != 0) report.over_paths.back().emplace_back(m[1], type);
    }
  }
  if (section != Section::Tail) throw std::runtime_error("the timing report stops early");
  std::stable_sort(report.endpoints.begin(), report.endpoints.end(),
                   [](const StaEndpoint& a, const StaEndpoint& b) { return a.period_ns > b.period_ns; });
  return report;
}

StaReport time_netlist(const std::vector<fs::path>& netlists, const std::string& top, const std::string& liberty,
                       const std::string& clock, const fs::path& work, double over_ns, int max_paths) {
  if (netlists.empty()) throw std::invalid_argument("time_netlist: no netlist");
  const fs::path& netlist = netlists.front();
  std::string reads;
  for (const fs::path& file : netlists) reads += "read_verilog " + file.string() + "\n";
  const fs::path script = work / "sta.tcl";
  const fs::path log = work / "sta.log";
  // Every flip-flop's worst path (-format end, one line an endpoint), then
  // the worst path in full. Unconstrained inputs launch no path and outputs
  // end none, so these are the paths from a flip-flop to a flip-flop.
  write_file_atomic(script, fmt::format(
      "read_liberty {lib}\n"
      "{reads}"
      "link_design {top}\n"
      "create_clock -name clk -period {period} [get_ports {clock}]\n"
      "foreach c [get_cells -hierarchical *] {{\n"
      "  if {{![$c is_leaf]}} {{ puts \"{instance}[get_full_name $c] [get_property $c ref_name]\" }}\n"
      "}}\n"
      "puts {endpoints}\n"
      "report_checks -path_delay max -format end -group_count 100000000 -endpoint_count 1 -digits 4\n"
      "puts {worst}\n"
      "report_checks -path_delay max -digits 3 -fields {{fanout cap slew}}\n"
      "{over}"
      "puts {end}\n",
      fmt::arg("lib", liberty), fmt::arg("reads", reads), fmt::arg("top", top),
      fmt::arg("period", kClockPeriodNs), fmt::arg("clock", clock), fmt::arg("instance", kInstance),
      fmt::arg("endpoints", kEndpoints), fmt::arg("worst", kWorst), fmt::arg("end", kEnd),
      fmt::arg("over", over_ns > 0 ? fmt::format("puts {}\nreport_checks -path_delay max -group_count {} "
                                                 "-endpoint_count 1 -slack_max {:.4f} -digits 3\n",
                                                 kOver, max_paths, kClockPeriodNs - over_ns)
                                   : "")));
  const auto started = std::chrono::steady_clock::now();
  std::error_code ec;
  fs::remove(log, ec);
  int status = -1;
  try {
    status = run_child({"sta", "-no_splash", "-exit", script.string()}, log);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(fmt::format("{} (OpenSTA: Debian's opensta, which scripts/setup installs)", e.what()));
  }
  if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0))
    throw std::runtime_error(fmt::format("OpenSTA failed timing {} ({}; {})", netlist.string(),
                                         describe_status(status), log.string()));
  StaReport report;
  try {
    report = parse_sta_log(read_text_file(log), kClockPeriodNs);
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("OpenSTA timing {}: {} ({})", netlist.string(), e.what(), log.string()));
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return report;
}

}  // namespace cdsim
