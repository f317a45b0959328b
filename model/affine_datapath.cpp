#include "affine_datapath.hpp"

namespace cdsim {

namespace {

fx::Wide divide_nearest(fx::Wide numerator, fx::Wide denominator) {
  if (denominator < 0) numerator = -numerator, denominator = -denominator;
  return fx::floor_div(2 * numerator + denominator, 2 * denominator);
}

// u, v in affine_format scaled by 2^extra_shift, rounded to the output format.
CorrectedValue to_output(fx::Wide u, fx::Wide v, const Widths& w, int extra_shift = 0) {
  CorrectedValue out;
  const int from_frac = w.s_frac + extra_shift;
  const fx::Format format = w.out_format();
  out.u = static_cast<int64_t>(fx::narrow(u, from_frac, format, fx::Round::Nearest, fx::Overflow::Saturate,
                                          &out.saturated));
  out.v = static_cast<int64_t>(fx::narrow(v, from_frac, format, fx::Round::Nearest, fx::Overflow::Saturate,
                                          &out.saturated));
  return out;
}

}  // namespace

AffinePlanes affine_setup(const UnitTriangle& t, const Setup& s, const Widths& w) {
  AffinePlanes p;
  const auto& v = t.vertex;
  const fx::Wide dx1 = v[1].x - v[0].x, dy1 = v[1].y - v[0].y;
  const fx::Wide dx2 = v[2].x - v[0].x, dy2 = v[2].y - v[0].y;
  const fx::Wide det = s.edges.det;
  const int sp = w.subpixel_bits;
  const fx::Wide half = fx::Wide{1} << (sp - 1);
  const fx::Wide ref_x = fx::Wide{s.box.x_lo} * (fx::Wide{1} << sp) + half - v[0].x;
  const fx::Wide ref_y = fx::Wide{s.box.y_lo} * (fx::Wide{1} << sp) + half - v[0].y;
  // value * 2^s_frac = numerator / (det * 2^uv_in_frac)
  const fx::Wide scale = fx::Wide{1} << w.s_frac;
  const fx::Wide denominator = det * (fx::Wide{1} << w.uv_in_frac);
  const fx::Format ref_format = affine_format(w), step_format = w.s_format();
  const auto plane = [&](int64_t a0, int64_t a1, int64_t a2, int64_t* ref, int64_t* major,
                         int64_t* minor) {
    const fx::Wide da1 = a1 - a0, da2 = a2 - a0;
    const fx::Wide coef_x = da1 * dy2 - da2 * dy1, coef_y = da2 * dx1 - da1 * dx2;
    const fx::Wide at_ref = fx::Wide{a0} * det + coef_x * ref_x + coef_y * ref_y;
    const fx::Wide per_x = coef_x * (fx::Wide{1} << sp), per_y = coef_y * (fx::Wide{1} << sp);
    *ref = static_cast<int64_t>(fx::fit(divide_nearest(at_ref * scale, denominator), ref_format,
                                        fx::Overflow::Saturate, &p.saturated));
    const fx::Wide step_major = s.x_major ? per_x : per_y, step_minor = s.x_major ? per_y : per_x;
    *major = static_cast<int64_t>(fx::fit(divide_nearest(step_major * scale, denominator),
                                          step_format, fx::Overflow::Saturate, &p.saturated));
    *minor = static_cast<int64_t>(fx::fit(divide_nearest(step_minor * scale, denominator),
                                          step_format, fx::Overflow::Saturate, &p.saturated));
  };
  plane(v[0].u, v[1].u, v[2].u, &p.u_ref, &p.u_major, &p.u_minor);
  plane(v[0].v, v[1].v, v[2].v, &p.v_ref, &p.v_major, &p.v_minor);
  return p;
}

CorrectedValue affine_pixel(const AffinePlanes& p, int64_t major_offset, int64_t minor_offset,
                            const Widths& w) {
  CorrectedValue out = to_output(p.u_ref + major_offset * p.u_major + minor_offset * p.u_minor,
                                 p.v_ref + major_offset * p.v_major + minor_offset * p.v_minor, w);
  out.saturated |= p.saturated;
  return out;
}

CorrectedValue interpolate_segment(const CorrectedValue& a, const CorrectedValue& b, int64_t length,
                                   int64_t position, const Widths& w) {
  const auto step = [&](int64_t from, int64_t to) {
    return static_cast<int64_t>(divide_nearest(fx::Wide{to} - from, length));
  };
  CorrectedValue out = to_output(a.u + position * step(a.u, b.u), a.v + position * step(a.v, b.v), w);
  out.saturated |= a.saturated || b.saturated;
  return out;
}

int64_t quadratic_segment_length(int64_t remaining, int64_t segment) {
  if (remaining >= segment) return segment;
  int64_t length = 1;
  while (2 * length <= remaining) length *= 2;
  return length;
}

CorrectedValue quadratic_segment(const CorrectedValue& a, const CorrectedValue& m, const CorrectedValue& b,
                                 int64_t length, int64_t position, const Widths& w) {
  CorrectedValue out;
  if (length == 1) {
    out = to_output(position == 0 ? a.u : b.u, position == 0 ? a.v : b.v, w);
    out.saturated |= a.saturated || b.saturated;
    return out;
  }
  // With h = length / 2, the quadratic times 2 h^2 at p is
  //   2 h^2 a + p ((4m - 3a - b) h + (a - 2m + b)) + p (p - 1) (a - 2m + b):
  // a at 0, m at h, b at 2h, and its forward differences are integers.
  const fx::Wide h = length / 2, p = position;
  const auto at = [&](fx::Wide fa, fx::Wide fm, fx::Wide fb) {
    const fx::Wide curve = fa - 2 * fm + fb;
    return 2 * h * h * fa + p * ((4 * fm - 3 * fa - fb) * h + curve) + p * (p - 1) * curve;
  };
  int scale = 1;  // log2(2 h^2)
  while ((fx::Wide{1} << scale) < 2 * h * h) ++scale;
  out = to_output(at(a.u, m.u, b.u), at(a.v, m.v, b.v), w, scale);
  out.saturated |= a.saturated || m.saturated || b.saturated;
  return out;
}

}  // namespace cdsim
