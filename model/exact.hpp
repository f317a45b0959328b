// The exact reference of SPEC §2: q = 1/w, U = u q and V = v q are affine in
// screen space over the snapped triangle; u* = U/q and v* = V/q at each pixel
// centre, in long double. Every error in cdsim is measured against this.
#pragma once

#include <array>

#include "pixel_coverage.hpp"
#include "triangle.hpp"

namespace cdsim {

struct ExactSample {
  long double u = 0, v = 0;
  long double footprint = 0;  // rho: the longer of |d(u,v)/dx| and |d(u,v)/dy|
  long double q = 0;          // 1/w at the pixel centre (larger is nearer)
};

class ExactReference {
 public:
  // Uses the snapped x, y the unit sees and the unquantised w, u, v of the
  // screen triangle.
  ExactReference(const ScreenTriangle& screen, const UnitTriangle& unit, int subpixel_bits);

  ExactSample at_pixel(int64_t pixel_x, int64_t pixel_y) const;
  const EdgeSet& edges() const { return edges_; }

 private:
  EdgeSet edges_;
  std::array<long double, 3> q_{}, uq_{}, vq_{};
  // Gradients of sum_i E_i * attribute_i per pixel, which are constant.
  long double q_dx_ = 0, q_dy_ = 0, uq_dx_ = 0, uq_dy_ = 0, vq_dx_ = 0, vq_dy_ = 0;
};

}  // namespace cdsim
