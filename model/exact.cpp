#include "exact.hpp"

#include <algorithm>
#include <cmath>

namespace cdsim {

ExactReference::ExactReference(const ScreenTriangle& screen, const UnitTriangle& unit,
                               int subpixel_bits)
    : edges_(make_edges(unit, subpixel_bits)) {
  const long double pixel = std::ldexp(1.0L, subpixel_bits);
  for (size_t i = 0; i < 3; ++i) {
    const ScreenVertex& s = screen.vertex[i];
    q_[i] = 1.0L / static_cast<long double>(s.w);
    uq_[i] = static_cast<long double>(s.u) * q_[i];
    vq_[i] = static_cast<long double>(s.v) * q_[i];
    q_dx_ += edges_.a[i] * q_[i] * pixel;
    q_dy_ += edges_.b[i] * q_[i] * pixel;
    uq_dx_ += edges_.a[i] * uq_[i] * pixel;
    uq_dy_ += edges_.b[i] * uq_[i] * pixel;
    vq_dx_ += edges_.a[i] * vq_[i] * pixel;
    vq_dy_ += edges_.b[i] * vq_[i] * pixel;
  }
}

ExactSample ExactReference::at_pixel(int64_t pixel_x, int64_t pixel_y) const {
  const int64_t px = pixel_centre(pixel_x, edges_.subpixel_bits);
  const int64_t py = pixel_centre(pixel_y, edges_.subpixel_bits);
  // E_i is vertex i's barycentric weight times det, exact in 64-bit integers;
  // det cancels in every ratio below.
  long double q = 0, uq = 0, vq = 0;
  for (size_t i = 0; i < 3; ++i) {
    const long double weight =
        static_cast<long double>(edges_.a[i] * px + edges_.b[i] * py + edges_.c[i]);
    q += weight * q_[i];
    uq += weight * uq_[i];
    vq += weight * vq_[i];
  }
  ExactSample s;
  s.q = q / std::fabs(static_cast<long double>(edges_.det));  // E_i sum to |det|
  s.u = uq / q;
  s.v = vq / q;
  const long double du_dx = (uq_dx_ - s.u * q_dx_) / q, dv_dx = (vq_dx_ - s.v * q_dx_) / q;
  const long double du_dy = (uq_dy_ - s.u * q_dy_) / q, dv_dy = (vq_dy_ - s.v * q_dy_) / q;
  // One square root of the larger squared length, not two hypotl calls (a
  // third of the error measurement's time): long double's range leaves no
  // overflow for hypot to guard against here.
  s.footprint = std::sqrt(std::max(du_dx * du_dx + dv_dx * dv_dx, du_dy * du_dy + dv_dy * dv_dy));
  return s;
}

}  // namespace cdsim
