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
  CorrectedValue out;
  out.u = static_cast<int64_t>(
      quotient(at(s.u), w.uv_in_frac, r, w.recip_bits, format, w.quotient_guard_bits, &out.saturated));
  out.v = static_cast<int64_t>(
      quotient(at(s.v), w.uv_in_frac, r, w.recip_bits, format, w.quotient_guard_bits, &out.saturated));
  return out;
}

}  // namespace cdsim
