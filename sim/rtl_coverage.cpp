#include "rtl_coverage.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <tuple>

#include "cache_files.hpp"
#include "build_info.hpp"
#include "rtl_build.hpp"
#include "regress.hpp"
#include "rtl_cache.hpp"

namespace cdsim::rtl {

namespace fs = std::filesystem;

std::string coverage_data_path(const std::string& dir, const std::string& widths, const std::string& source,
                               const std::string& design, double backpressure, const std::string& shard,
                               int64_t only) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir))
    throw std::invalid_argument(fmt::format("--coverage {}: cannot make this folder{}", dir,
                                            ec ? ": " + ec.message() : ""));
  const std::string run = fmt::format("widths {}\nsource {}\ndesign {}\nbackpressure {}\nshard {}\nonly {}",
                                      widths, source, design, backpressure, shard, only);
  return (fs::path(dir) / fmt::format("run-{:016x}.dat", fnv1a(run))).string();
}

namespace {

// Verilator's data: "C '<key>\002<value>\001<key>\002<value>...' <count>".
std::map<std::string, std::string> point_fields(const std::string& text, const std::string& where) {
  std::map<std::string, std::string> fields;
  size_t at = 0;
  while (at < text.size()) {
    if (text[at] == '\001') {
      ++at;
      continue;
    }
    const size_t sep = text.find('\002', at);
    if (sep == std::string::npos) throw std::runtime_error(where + ": a key without a value");
    size_t end = text.find('\001', sep + 1);
    if (end == std::string::npos) end = text.size();
    fields[text.substr(at, sep - at)] = text.substr(sep + 1, end - sep - 1);
    at = end;
  }
  return fields;
}

// Whether `file` lies in rtl/ ("rtl") or in sim/cover ("cover"), else "";
// resolved once per file, not once per point.
std::string where_of(const std::string& file) {
  static const std::string rtl = fs::weakly_canonical(kRtlDir).string() + "/";
  static const std::string cover = fs::weakly_canonical(fs::path(build::kCoverSource).parent_path()).string() + "/";
  static std::map<std::string, std::string> known;
  const auto it = known.find(file);
  if (it != known.end()) return it->second;
  const std::string f = fs::weakly_canonical(file).string();
  return known[file] = f.rfind(rtl, 0) == 0 ? "rtl" : f.rfind(cover, 0) == 0 ? "cover" : "";
}

}  // namespace

std::vector<CoveragePoint> read_coverage(const std::vector<std::string>& dat_files) {
  std::map<std::tuple<std::string, int, std::string, std::string, std::string>, CoveragePoint> merged;
  for (const std::string& path : dat_files) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(fmt::format("{}: cannot read", path));
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      if (line.empty() || line[0] == '#') continue;
      const std::string where = fmt::format("{}:{}", path, number);
      const size_t open = line.find('\'');
      const size_t close = line.rfind('\'');
      if (line.rfind("C ", 0) != 0 || open == std::string::npos || close <= open)
        throw std::runtime_error(where + ": not a Verilator coverage point");
      const auto fields = point_fields(line.substr(open + 1, close - open - 1), where);
      CoveragePoint p;
      try {
        p.count = std::stoull(line.substr(close + 1));
        p.line = fields.count("l") ? std::stoi(fields.at("l")) : 0;
      } catch (const std::exception&) {
        throw std::runtime_error(where + ": a count or line that is not a number");
      }
      p.file = fields.count("f") ? fields.at("f") : "";
      const std::string page = fields.count("page") ? fields.at("page") : "";
      // "v_line/cd_scan_unit", "v_toggle/...", "v_branch/...", "v_user/..."
      p.type = page.rfind("v_", 0) == 0 ? page.substr(2, page.find('/') - 2) : page;
      p.comment = fields.count("o") ? fields.at("o") : "";
      const std::string column = fields.count("n") ? fields.at("n") : "";
      auto [it, added] = merged.try_emplace({p.file, p.line, p.type, p.comment, column}, p);
      if (!added) it->second.count += p.count;
    }
  }
  std::vector<CoveragePoint> out;
  out.reserve(merged.size());
  for (auto& [key, p] : merged) out.push_back(std::move(p));
  return out;
}

std::map<std::string, CoverageFigures> coverage_figures(const std::vector<CoveragePoint>& points) {
  std::map<std::string, CoverageFigures> out;
  for (const CoveragePoint& p : points) {
    const std::string where = where_of(p.file);
    if (!(where == "rtl" || (p.type == "user" && where == "cover"))) continue;
    CoverageFigures& f = out[p.type];
    ++f.total;
    if (p.count > 0) ++f.covered;
  }
  return out;
}

std::map<std::string, CoverageFigures> report_coverage(const std::string& dir,
                                                       const std::vector<std::string>& more_dirs) {
  // One report at a time in DIR (shards of a regression may end together).
  const int lock = ::open((fs::path(dir) / ".lock").c_str(), O_CREAT | O_RDWR, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX) != 0)
    throw std::runtime_error(fmt::format("{}: cannot lock {}", dir, (fs::path(dir) / ".lock").string()));
  struct Unlock {
    int fd;
    ~Unlock() { ::close(fd); }
  } unlock{lock};
  std::vector<std::string> dat;
  for (const std::string& d : [&] {
         std::vector<std::string> all = {dir};
         all.insert(all.end(), more_dirs.begin(), more_dirs.end());
         return all;
       }()) {
    if (!fs::is_directory(d)) throw std::runtime_error(fmt::format("{}: not a folder", d));
    for (const auto& entry : fs::directory_iterator(d))
      if (entry.path().extension() == ".dat") dat.push_back(entry.path().string());
  }
  std::sort(dat.begin(), dat.end());
  if (dat.empty()) throw std::runtime_error(fmt::format("{}: no coverage data (*.dat) to report", dir));
  const std::vector<CoveragePoint> points = read_coverage(dat);
  const auto figures = coverage_figures(points);

  // lcov .info of everything, merged by Verilator's own tool, and its HTML.
  const fs::path info = fs::path(dir) / "coverage.info";
  std::vector<std::string> merge = {build::kVerilatorCoverageBin, "--write-info", info.string()};
  merge.insert(merge.end(), dat.begin(), dat.end());
  run_tool(merge, (fs::path(dir) / "verilator_coverage.log").string(), "verilator_coverage");
  run_tool({"genhtml", "--quiet", "--output-directory", (fs::path(dir) / "html").string(), "--title",
            "cdsim RTL coverage", info.string()},
           (fs::path(dir) / "genhtml.log").string(), "genhtml");

  nlohmann::json by_type = nlohmann::json::object();
  nlohmann::json uncovered = nlohmann::json::array();
  for (const auto& [type, f] : figures)
    by_type[type] = {{"covered", f.covered}, {"total", f.total}, {"percent", f.percent()}};
  for (const CoveragePoint& p : points)
    if (p.count == 0 && p.type != "toggle" && !where_of(p.file).empty())
      uncovered.push_back({{"file", fs::path(p.file).filename().string()}, {"line", p.line},
                           {"type", p.type}, {"point", p.comment}});
  write_file_atomic(fs::path(dir) / "coverage.json",
                    nlohmann::json{{"runs", dat.size()}, {"rtl", by_type}, {"uncovered", uncovered}}.dump(2) +
                        "\n");

  std::cout << fmt::format("coverage of rtl/ over the {} runs in {}:\n", dat.size(), dir);
  for (const auto& [type, f] : figures)
    std::cout << fmt::format("  {:<7} {:>6.2f}%  ({} of {} points)\n", type, f.percent(), f.covered, f.total);
  std::cout << fmt::format("uncovered line, branch and cover points: {} (in {}); report: {}\n",
                           uncovered.size(), (fs::path(dir) / "coverage.json").string(),
                           (fs::path(dir) / "html" / "index.html").string());
  return figures;
}

int run_coverage_command(const CoverageOptions& options) {
  try {
    const std::vector<std::string> more(options.dirs.begin() + 1, options.dirs.end());
    const auto figures = report_coverage(options.dirs.front(), more);
    const auto line = figures.find("line");
    const double lines = line == figures.end() ? 0.0 : line->second.percent();
    if (lines < options.min_lines) {
      std::cerr << fmt::format("cdsim coverage: line coverage of rtl/ is {:.2f}%, below --min-lines {}\n",
                               lines, options.min_lines);
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "cdsim coverage: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace cdsim::rtl
