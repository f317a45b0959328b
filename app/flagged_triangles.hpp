// `cdsim run --flagged FILE`: every triangle whose pixels carry a datapath
// flag, per design, with the geometry behind it (model/line_geometry.hpp):
// a readable table of the worst on stdout and every row as CSV (issue 41,
// docs/robustness.md "Flagged triangles").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "evaluate.hpp"
#include "line_geometry.hpp"

namespace cdsim {

class FlaggedTriangles {
 public:
  FlaggedTriangles(const PreparedScene& scene, const Widths& widths) : scene_(scene), widths_(widths) {}
  // Around one design's evaluate(), whose visitor calls add().
  void start(const Design& design);
  void add(int64_t triangle, const Fragment& fragment, const ExactSample& exact);
  void finish();
  // The rows of another collector (of later designs) after this one's.
  void append(FlaggedTriangles&& other);

  std::string csv() const;
  std::string table(size_t rows_per_design) const;
  size_t size() const { return rows_.size(); }

 private:
  struct Tally {
    int64_t pixels = 0, flagged = 0;
    uint32_t flags = 0;
    double error_max = 0, footprint_max = 0;
  };
  struct Row {
    std::string design;
    int64_t triangle = 0;
    Tally tally;
    bool has_lines = false;  // a constant-depth design: the geometry below is set
    LineGeometry geometry;
  };

  const PreparedScene& scene_;
  const Widths& widths_;
  Design design_;
  std::vector<Tally> tallies_;  // the running design's, by triangle
  std::vector<Row> rows_;
};

}  // namespace cdsim
