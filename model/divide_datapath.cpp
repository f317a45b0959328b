#include "divide_datapath.hpp"

#include "derived_widths.hpp"

namespace cdsim {

CorrectedValue divide_uv(const Setup& s, int64_t major_offset, int64_t minor_offset,
                         const Widths& w, const fx::Format& format, uint32_t* flags) {
  const auto at = [&](const Plane& p) { return p.at(major_offset, minor_offset); };
  fits_or_throw(at(s.q), s.pixel_q_bits, "q at a pixel");
  fits_or_throw(at(s.u), s.pixel_uv_bits, "U at a pixel");
  fits_or_throw(at(s.v), s.pixel_uv_bits, "V at a pixel");
  const Reciprocal r = reciprocal(at(s.q), w.recip_bits);
  if (r.out_of_range) *flags |= flag::kDepthRange;
  const int product_frac = w.recip_bits + r.exponent + w.uv_in_frac;
  CorrectedValue out;
  out.u = static_cast<int64_t>(fx::narrow(at(s.u) * r.mantissa, product_frac, format,
                                          fx::Round::Nearest, fx::Overflow::Saturate, &out.saturated));
  out.v = static_cast<int64_t>(fx::narrow(at(s.v) * r.mantissa, product_frac, format,
                                          fx::Round::Nearest, fx::Overflow::Saturate, &out.saturated));
  return out;
}

}  // namespace cdsim
