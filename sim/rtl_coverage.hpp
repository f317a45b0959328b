// RTL coverage of `cdsim regress --coverage DIR` (docs/coverage.md).
//
// Each run writes its Verilator coverage data as DIR/<run key>.dat, the key
// naming what the run covered (widths, source, design, back-pressure, shard),
// so a rerun replaces its own data and other runs add theirs. After each run
// the report of everything in DIR is made again: the points merged by
// verilator_coverage into DIR/coverage.info (lcov), genhtml's HTML in DIR/html,
// and the figures per kind of point in DIR/coverage.json and on stdout.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace cdsim::rtl {

// DIR/<key>.dat for a run; creates DIR. Throws naming --coverage when DIR
// cannot be a folder.
std::string coverage_data_path(const std::string& dir, const std::string& widths, const std::string& source,
                               const std::string& design, double backpressure, const std::string& shard,
                               int64_t only);

// One coverage point of Verilator's data, counts summed over the files read.
struct CoveragePoint {
  std::string file;     // as Verilator names it
  int line = 0;
  std::string type;     // line, branch, toggle or user (from the point's page "v_<type>/...")
  std::string comment;  // the signal, block or cover point
  uint64_t count = 0;
};

// The points of Verilator coverage.dat files, merged as verilator_coverage
// merges them (same point: counts added). Throws naming the file and line of
// anything it cannot read.
std::vector<CoveragePoint> read_coverage(const std::vector<std::string>& dat_files);

struct CoverageFigures {
  int64_t covered = 0, total = 0;
  double percent() const { return total ? 100.0 * double(covered) / double(total) : 0.0; }
};
// Per type, over the points in files under rtl/ ("user" over sim/cover).
std::map<std::string, CoverageFigures> coverage_figures(const std::vector<CoveragePoint>& points);

// Merges DIR/*.dat (and those of `more_dirs`) into DIR/coverage.info and
// DIR/coverage.json, makes the HTML report in DIR/html, prints the figures and
// returns them. Throws when a tool fails or there is no data.
std::map<std::string, CoverageFigures> report_coverage(const std::string& dir,
                                                       const std::vector<std::string>& more_dirs = {});

}  // namespace cdsim::rtl
