// The adaptive-subdivision baseline (Kamen & Shirman 1998; docs/designs.md,
// "adaptive"): the split engine in front of a plain affine unit. A triangle
// is split in four at its edge midpoints while linear interpolation misses
// u or v at one of those midpoints by more than 2^-adapt_bound_frac texels,
// at most adapt_depth times; each leaf is then a triangle of its own for the
// affine unit. Plain functions of values; the cycles of the split engine are
// counted here too (one number per leaf), the unit's by its own schedule.
#pragma once

#include <cstdint>
#include <vector>

#include "triangle.hpp"
#include "widths.hpp"

namespace cdsim {

// The widths of the affine unit behind the split engine: adaptive_leaf_widths
// (widths.hpp).

struct AdaptiveLeaf {
  UnitTriangle triangle;  // at adaptive_leaf_widths
  int depth = 0;          // 0: the triangle itself
  // Split-engine cycles from the cycle after the unit accepted the leaf before
  // (for a triangle's first leaf: from its root node's first cycle) to the
  // cycle this leaf is offered, not counting that cycle (docs/designs.md).
  int64_t engine_cycles = 0;
};

struct AdaptiveSplit {
  std::vector<AdaptiveLeaf> leaves;  // depth first: corners A, B, C, then the middle
  // Split-engine cycles after the last leaf's acceptance: the nodes dropped
  // after it (empty boxes).
  int64_t tail_cycles = 0;
  int64_t splits = 0;       // nodes split in four
  int64_t evaluations = 0;  // nodes whose midpoints were divided and tested
  int64_t dropped = 0;      // sub-triangles with no pixel centre in their box: never sent
  uint32_t flags = 0;       // kDepthRange (a 1/w of 0), kOutputSaturated (a midpoint's u or v)
};

// Split-engine timing (docs/designs.md): the cycles of the intake of a
// triangle (1/w normalised, U = u q and V = v q), of one node's evaluation
// (the midpoints; three reciprocals issued on one pipelined unit, each
// result multiplied and narrowed in the cycle it arrives; the tests), and
// of dropping a node with an empty box.
inline constexpr int64_t kAdaptiveIntakeCycles = 2;
inline int64_t adaptive_evaluation_cycles(const Widths& widths) { return 1 + 3 + widths.recip_latency + 1; }
inline constexpr int64_t kAdaptiveDropCycles = 1;

AdaptiveSplit adaptive_split(const UnitTriangle& triangle, const Widths& widths, int viewport_width,
                             int viewport_height);

}  // namespace cdsim
