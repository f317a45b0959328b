#include "kim_datapath.hpp"

#include "derived_widths.hpp"

namespace cdsim {

KimPixel kim_pixel(const Setup& s, int64_t major_offset, int64_t minor_offset, const Widths& w,
                   const KimPixel* previous, uint32_t* flags) {
  const auto at = [&](const Plane& p) { return p.at(major_offset, minor_offset); };
  // The RTL takes a span's first N and D from the per-pixel plane accumulators.
  fits_or_throw(at(s.q), s.pixel_q_bits, "q at a pixel");
  fits_or_throw(at(s.u), s.pixel_uv_bits, "U at a pixel");
  fits_or_throw(at(s.v), s.pixel_uv_bits, "V at a pixel");
  // N carries uv_in_frac fraction bits of texels over q's scale: fold them into D
  // so that I = floor(N / D) counts whole texels.
  const fx::Wide d = at(s.q) * (fx::Wide{1} << w.uv_in_frac);
  KimPixel out;
  if (d <= 0) {
    // No steps: the iteration holds I (R += S keeps R = N - I D).
    *flags |= flag::kDepthRange;
    out.depth_out = true;
    if (previous) {
      out.integer_u = previous->integer_u;
      out.integer_v = previous->integer_v;
    }
    return out;
  }
  const fx::Format format = w.out_format();
  const auto coordinate = [&](fx::Wide n, int64_t* integer) {
    const fx::Wide whole = fx::floor_div(n, d);
    const fx::Wide remainder = n - whole * d;  // 0 <= remainder < d
    const fx::Wide fraction = (remainder * (fx::Wide{1} << w.kim_frac)) / d;
    bool saturated = false;
    // The integer register is out_int bits wide; outside it the output saturates.
    const fx::Wide clamped = fx::fit(whole, {w.out_int, 0, true}, fx::Overflow::Saturate, &saturated);
    *integer = static_cast<int64_t>(clamped);
    const fx::Wide raw = whole * (fx::Wide{1} << w.kim_frac) + fraction;
    const auto value = static_cast<int64_t>(
        fx::narrow(raw, w.kim_frac, format, fx::Round::Nearest, fx::Overflow::Saturate, &saturated));
    out.value.saturated |= saturated;
    return value;
  };
  out.value.u = coordinate(at(s.u), &out.integer_u);
  out.value.v = coordinate(at(s.v), &out.integer_v);
  return out;
}

}  // namespace cdsim
