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

#include "timing.hpp"
#include "triangle.hpp"
#include "widths.hpp"

namespace cdsim {

// The widths of the affine unit behind the split engine: adaptive_leaf_widths
// (widths.hpp).

struct AdaptiveLeaf {
  UnitTriangle triangle;  // at adaptive_leaf_widths
  int depth = 0;          // 0: the triangle itself
  // The split engine's work from the leaf before's acceptance (for a
  // triangle's first leaf: from its root node's first cycle) to this leaf's
  // offer; model/timing.hpp prices it (split_engine_cycles).
  SplitEngineWork work;
};

struct AdaptiveSplit {
  std::vector<AdaptiveLeaf> leaves;  // depth first: corners A, B, C, then the middle
  // The split engine's work after the last leaf's acceptance: the nodes
  // dropped after it (empty boxes).
  SplitEngineWork tail;
  int64_t splits = 0;       // nodes split in four
  int64_t evaluations = 0;  // nodes whose midpoints were divided and tested
  int64_t dropped = 0;      // sub-triangles with no pixel centre in their box: never sent
  uint32_t flags = 0;       // kDepthRange (a 1/w of 0), kOutputSaturated (a midpoint's u or v)
};

AdaptiveSplit adaptive_split(const UnitTriangle& triangle, const Widths& widths, int viewport_width,
                             int viewport_height);

}  // namespace cdsim
