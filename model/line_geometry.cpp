#include "line_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cdsim {

int signed_int_bits_for(double largest) {
  if (!(largest >= 1)) return 1;
  return static_cast<int>(std::floor(std::log2(largest))) + 2;
}

LineGeometry line_geometry(const ScreenTriangle& screen, const UnitTriangle& unit, const Setup& s,
                           const Widths& w) {
  using LD = long double;
  LineGeometry g;
  g.x_major = s.x_major;

  // The exact plane of q = 1/w over the snapped vertices (SPEC §2).
  std::array<LD, 3> x{}, y{}, q{};
  for (size_t i = 0; i < 3; ++i) {
    x[i] = snapped_pixels(unit.vertex[i].x, w.subpixel_bits);
    y[i] = snapped_pixels(unit.vertex[i].y, w.subpixel_bits);
    q[i] = 1.0L / static_cast<LD>(screen.vertex[i].w);
  }
  const LD det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
  const LD q_min = *std::min_element(q.begin(), q.end()), q_max = *std::max_element(q.begin(), q.end());
  g.depth_ratio = static_cast<double>(q_max / q_min);
  if (det != 0) {
    const LD dq_dx = ((q[1] - q[0]) * (y[2] - y[0]) - (q[2] - q[0]) * (y[1] - y[0])) / det;
    const LD dq_dy = ((q[2] - q[0]) * (x[1] - x[0]) - (q[1] - q[0]) * (x[2] - x[0])) / det;
    const LD per_line = std::fabs(s.x_major ? dq_dy : dq_dx) / s.density;
    g.horizon_gaps = per_line > 0 ? static_cast<double>(q_min / per_line) : std::numeric_limits<double>::infinity();
  } else {
    g.horizon_gaps = std::numeric_limits<double>::infinity();
  }

  // The lines the table holds and what T and S are on them.
  if (s.empty || s.pixel_line_lo > s.pixel_line_hi) return g;
  const int64_t guard = s.correction ? 1 : 0;
  const LD uv_scale = std::ldexp(1.0L, -w.uv_in_frac);
  LD t_max = 0, s_max = 0;
  for (int64_t k = s.pixel_line_lo - guard; k <= s.pixel_line_hi + guard; ++k) {
    ++g.lines;
    const LD q_k = static_cast<LD>(plane_on_line(s, s.q, k));
    if (q_k <= 0) {
      ++g.past_horizon;
      continue;
    }
    const LD t_u = static_cast<LD>(plane_on_line(s, s.u, k)) * uv_scale / q_k;
    const LD t_v = static_cast<LD>(plane_on_line(s, s.v, k)) * uv_scale / q_k;
    const LD s_u = static_cast<LD>(s.step_u) * uv_scale / q_k;
    const LD s_v = static_cast<LD>(s.step_v) * uv_scale / q_k;
    t_max = std::max({t_max, std::fabs(t_u), std::fabs(t_v)});
    s_max = std::max({s_max, std::fabs(s_u), std::fabs(s_v)});
  }
  g.t_max = static_cast<double>(t_max);
  g.s_max = static_cast<double>(s_max);
  g.t_int_needed = signed_int_bits_for(g.t_max);
  g.s_int_needed = signed_int_bits_for(g.s_max);
  return g;
}

}  // namespace cdsim
