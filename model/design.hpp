// The datapath designs cdsim compares, by the names the CLI and reports use.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "encodings.hpp"

namespace cdsim {

struct Design {
  // The values are the RTL's kind_i (encodings.def). Adaptive is none of
  // them: its own unit (rtl/adaptive_unit.sv) puts a split engine in front
  // of a scan unit that walks its leaves as affine.
  enum class Kind {
    ConstantDepth = encoding::KIND_CONSTANT_DEPTH,
    Divide = encoding::KIND_DIVIDE,
    Kim = encoding::KIND_KIM,
    Affine = encoding::KIND_AFFINE,
    Adaptive = 1 << encoding::KIND_BITS
  };
  std::string name;
  Kind kind = Kind::ConstantDepth;
  int density = 1;          // constant-depth lines per pixel (method 1: 2, 4)
  bool correction = false;  // linear correction between neighbouring lines (method 2)
  bool pipelined = false;   // Kim: fraction by a pipelined divider (else iterative)
  int subdivision = 0;      // Affine: exact divide every this many pixels (0: plain affine)
  std::string summary;
  // Constant depth with correction: the perspective-correct weight from the
  // line's q ratio (cd-persp, docs/designs.md) instead of the linear |d|.
  bool persp = false;
  // Affine kind, subdivided: a quadratic through three exact points per
  // segment (quad-subN, docs/designs.md) instead of a line through two.
  bool quadratic = false;
  // Constant depth with a divide fallback (cd-linear-div, cd-persp-div): a
  // triangle whose far vertex lies within 2^fallback_gaps_log2 line gaps of
  // its horizon is walked by divide's per-pixel datapath instead of the
  // table (docs/robustness.md, "The divide fallback").
  bool fallback = false;
  // The widths its accuracy depends on, in the order `cdsim size` sizes them.
  std::vector<std::string> sized_widths;
  // The default sweep's axes, as a sweep file writes them ("g_frac=6:20:2"),
  // each on its own around the defaults or, with sweep_grid, in every combination.
  std::vector<std::string> sweep_axes;
  bool sweep_grid = false;
};

// "constant_depth", "divide", "kim", "affine", "adaptive".
const char* kind_name(Design::Kind kind);
// The designs of model/designs.def, in its order.
const std::vector<Design>& all_designs();
// The RTL top that implements a design: the scan unit (rtl/cd_scan_unit.sv,
// one or several designs by parameter and kind_i), or the adaptive design's
// own unit (rtl/adaptive_unit.sv: its split engine and an affine scan unit).
enum class RtlTop { ScanUnit, AdaptiveUnit };
RtlTop rtl_top(const Design& design);
// Whether rtl/ implements the design (regress and area refuse the others).
bool has_rtl(const Design& design);
// The names of the designs with RTL, for messages: "cd-none, cd-linear, ...".
std::string rtl_design_names();
// Throws std::invalid_argument listing the known names.
const Design& find_design(const std::string& name);
// "a,b,c" -> designs; empty text -> all.
std::vector<Design> parse_design_list(const std::string& list);

// The unit's design inputs for one triangle (rtl/cd_scan_unit.sv: kind_i,
// segment_log2_i, kim_pipelined_i, density_log2_i, correction_i, persp_i,
// quadratic_i).
struct DesignSelect {
  int kind = 0;          // Design::Kind
  int segment_log2 = 0;  // affine-subN: log2 N; plain affine and the others: 0
  bool kim_pipelined = false;
  int density_log2 = 0;  // constant-depth lines per pixel m = 2^density_log2
  bool correction = false;
  bool persp = false;
  bool quadratic = false;  // affine-subN: quadratic segments (quad-subN)
  bool fallback = false;   // constant depth: near-horizon triangles by divide
};
inline int log2_ceil(int value) {
  int bits = 0;
  while ((1 << bits) < value) ++bits;
  return bits;
}
inline DesignSelect design_select(const Design& d) {
  DesignSelect s;
  s.kind = static_cast<int>(d.kind);
  s.segment_log2 = d.kind == Design::Kind::Affine ? log2_ceil(d.subdivision) : 0;
  s.kim_pipelined = d.kind == Design::Kind::Kim && d.pipelined;
  s.density_log2 = log2_ceil(d.density);
  s.correction = d.correction;
  s.persp = d.persp;
  s.quadratic = d.quadratic;
  s.fallback = d.fallback;
  return s;
}

// The parameters of rtl/cd_scan_unit.sv that elaborate a unit holding exactly
// the hardware these designs need: each one's datapath, a table as dense as
// the densest needs, the longest affine segment. In the unit's order, without
// HasObservation (synthesis turns it off, benches on). One design is what
// `cdsim area` synthesises; several are what a vectors bench elaborates.
struct UnitParameter {
  const char* name;
  int value;
};
std::vector<UnitParameter> unit_parameters(const std::vector<const Design*>& designs);
// "MaxDensityLog2=0 HasCorrection=1 ...", as reports name a unit.
std::string unit_parameter_list(const std::vector<UnitParameter>& parameters);

// Sticky per-triangle flags; a fragment carries the subset raised by its own pixel.
// Saturation is raised where a saturated value reaches an output: a table entry
// that saturated but that no fragment uses changes nothing and raises nothing.
namespace flag {
inline constexpr uint32_t kTableSaturated = 1u << encoding::FLAG_TABLE_SATURATED;     // T or S of some line saturated
inline constexpr uint32_t kOutputSaturated = 1u << encoding::FLAG_OUTPUT_SATURATED;   // an output u or v saturated
inline constexpr uint32_t kDepthRange = 1u << encoding::FLAG_DEPTH_RANGE;             // a 1/w left its format (<= 0 or underflow)
inline constexpr uint32_t kBanded = 1u << encoding::FLAG_BANDED;                      // more lines than the table holds: walked in bands
inline constexpr uint32_t kNeighbourDropped = 1u << encoding::FLAG_NEIGHBOUR_DROPPED; // correction skipped: the neighbour line was flagged
inline constexpr int kCount = encoding::count_of("FLAG");
// The flags that mark a pixel's value as possibly wrong (kBanded only says
// how the triangle was walked).
inline constexpr uint32_t kDatapath = kTableSaturated | kOutputSaturated | kDepthRange | kNeighbourDropped;
// "table_saturated", ... (encodings.def), "unknown" past kCount.
inline const char* name(int bit) { return encoding::lower_name("FLAG", bit); }
}  // namespace flag

}  // namespace cdsim
