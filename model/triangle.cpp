#include "triangle.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>

namespace cdsim {

namespace {

int64_t quantise(double value, int frac_bits) {
  return static_cast<int64_t>(std::nearbyint(std::ldexp(value, frac_bits)));
}

}  // namespace

UnitTriangle to_unit(const ScreenTriangle& triangle, const Widths& widths, size_t index) {
  UnitTriangle out;
  for (int i = 0; i < 3; ++i) {
    const ScreenVertex& s = triangle.vertex[static_cast<size_t>(i)];
    const auto refuse = [&](const std::string& what) {
      throw InputError(fmt::format("triangle {}{}: vertex {} {}", index,
                                   triangle.origin.empty() ? "" : " (" + triangle.origin + ")", i,
                                   what));
    };
    for (double value : {s.x, s.y, s.w, s.u, s.v})
      if (!std::isfinite(value))
        refuse(fmt::format("has a non-finite value (x={}, y={}, w={}, u={}, v={})", s.x, s.y, s.w,
                           s.u, s.v));
    if (!(s.w > 0)) refuse(fmt::format("has w = {} <= 0: it was not clipped at the near plane", s.w));
    const float q = static_cast<float>(1.0 / s.w);
    if (!std::isnormal(q))
      refuse(fmt::format("has w = {}, whose 1/w is not a normal binary32 number", s.w));
    if (std::fabs(s.x) >= kCoordinateLimit || std::fabs(s.y) >= kCoordinateLimit)
      refuse(fmt::format("lies at ({}, {}), outside the +-{} pixel range of 16.{} coordinates", s.x,
                         s.y, kCoordinateLimit, widths.subpixel_bits));
    if (std::fabs(s.u) >= kCoordinateLimit || std::fabs(s.v) >= kCoordinateLimit)
      refuse(fmt::format("has texture coordinates ({}, {}) outside +-{} texels", s.u, s.v,
                         kCoordinateLimit));
    UnitVertex& v = out.vertex[static_cast<size_t>(i)];
    v.x = quantise(s.x, widths.subpixel_bits);
    v.y = quantise(s.y, widths.subpixel_bits);
    std::memcpy(&v.q_float, &q, sizeof q);
    v.u = quantise(s.u, widths.uv_in_frac);
    v.v = quantise(s.v, widths.uv_in_frac);
  }
  return out;
}

}  // namespace cdsim
