#include "setup_engine.hpp"

#include <algorithm>
#include <cstring>

#include "derived_widths.hpp"

namespace cdsim {

using fx::Wide;

namespace {

struct Float32 {
  int exponent;       // biased
  int64_t mantissa;   // 24 bits, hidden bit set
};

Float32 unpack(uint32_t bits) {
  return {static_cast<int>((bits >> 23) & 0xff), static_cast<int64_t>((bits & 0x7fffff) | 0x800000)};
}

int log2_exact(int value) {
  int bits = 0;
  while ((1 << bits) < value) ++bits;
  return bits;
}

// round(numerator / denominator), ties toward +inf, denominator != 0.
Wide divide_nearest(Wide numerator, Wide denominator) {
  if (denominator < 0) numerator = -numerator, denominator = -denominator;
  return fx::floor_div(2 * numerator + denominator, 2 * denominator);
}

// The setup engine's serial dividers (stage C/D of rtl/setup_engine.sv): per
// edge the span end at the first column and its step per column.
std::array<EdgeTracker, 3> edge_trackers(const EdgeSet& e, bool x_major, int64_t major_lo,
                                         const DerivedWidths& dw) {
  std::array<EdgeTracker, 3> trackers{};
  const int sp = e.subpixel_bits;
  const int64_t one = int64_t{1} << sp;
  const int64_t half = one >> 1;
  for (size_t i = 0; i < 3; ++i) {
    const int64_t fixed = x_major ? e.a[i] : e.b[i];
    const int64_t free = x_major ? e.b[i] : e.a[i];
    const int64_t n = fixed * pixel_centre(major_lo, sp) + free * half + e.c[i] - e.threshold[i];
    fits_or_throw(n, dw.edge_n_bits, "edge value at the first column");
    EdgeTracker& t = trackers[i];
    t.kind = free > 0 ? 1 : (free < 0 ? 2 : 0);
    const int64_t free_abs = free < 0 ? -free : free;
    t.step = (t.kind == 0 ? 1 : free_abs) * one;
    t.bound = static_cast<int64_t>(fx::floor_div(n, t.step));
    t.remainder = n - t.bound * t.step;
    t.slope = static_cast<int64_t>(fx::floor_div(fixed * one, t.step));
    t.slope_remainder = fixed * one - t.slope * t.step;
    fits_or_throw(t.bound, dw.edge_bound_bits, "span end at the first column");
    fits_or_throw(t.slope, dw.edge_slope_bits, "span end step per column");
  }
  return trackers;
}

}  // namespace

std::array<Wide, 3> normalised_q(const UnitTriangle& t, const Widths& w) {
  std::array<Float32, 3> qf{};
  int max_exponent = 0;
  for (size_t i = 0; i < 3; ++i) {
    qf[i] = unpack(t.vertex[i].q_float);
    max_exponent = std::max(max_exponent, qf[i].exponent);
  }
  std::array<Wide, 3> q{};
  for (size_t i = 0; i < 3; ++i)
    q[i] = fx::shift_round(qf[i].mantissa, max_exponent - qf[i].exponent + 24 - w.q_bits,
                           fx::Round::Nearest);
  return q;
}

Setup setup_engine(const UnitTriangle& t, const Design& design, const Widths& w,
                   int viewport_width, int viewport_height) {
  return setup_engine(t, design, w, derive(w), viewport_width, viewport_height);
}

Setup setup_engine(const UnitTriangle& t, const Design& design, const Widths& w, const DerivedWidths& dw,
                   int viewport_width, int viewport_height) {
  Setup s;
  s.density = design.density;
  s.correction = design.correction;
  s.persp = design.persp;
  s.edges = make_edges(t, w.subpixel_bits);
  s.box = bounding_box(t, w.subpixel_bits, viewport_width, viewport_height);
  if (s.edges.det == 0 || s.box.empty()) return s;
  s.empty = false;
  // Every intermediate is checked against the width the RTL gives it.
  for (const UnitVertex& vertex : t.vertex) {
    fits_or_throw(vertex.x, dw.coord_bits, "vertex x");
    fits_or_throw(vertex.y, dw.coord_bits, "vertex y");
    fits_or_throw(vertex.u, dw.uv_bits, "vertex u");
    fits_or_throw(vertex.v, dw.uv_bits, "vertex v");
  }
  fits_or_throw(s.edges.det, dw.det_bits, "det");
  s.fill_q_bits = dw.fill_q_bits;
  s.fill_uv_bits = dw.fill_uv_bits;
  s.pixel_q_bits = dw.pixel_q_bits;
  s.pixel_uv_bits = dw.pixel_uv_bits;
  for (size_t i = 0; i < 3; ++i) fits_or_throw(s.edges.c[i], dw.edge_c_bits, "edge c");

  // Per-triangle normalisation of 1/w: align the three mantissas to the largest
  // exponent. The shared exponent itself cancels in u = U/q and is dropped.
  const std::array<Wide, 3> q = normalised_q(t, w);
  std::array<Wide, 3> uq{}, vq{};
  for (size_t i = 0; i < 3; ++i) {
    if (q[i] == 0) s.flags |= flag::kDepthRange;
    uq[i] = q[i] * t.vertex[i].u;
    vq[i] = q[i] * t.vertex[i].v;
    fits_unsigned_or_throw(q[i], dw.q_vertex_bits, "vertex q");
    fits_or_throw(uq[i], dw.attr_uv_bits, "vertex U");
    fits_or_throw(vq[i], dw.attr_uv_bits, "vertex V");
  }

  // Plane equations scaled by det (which cancels in every ratio we need), with
  // the sign chosen so that q * |det| > 0.
  const auto& v = t.vertex;
  const Wide dx1 = v[1].x - v[0].x, dy1 = v[1].y - v[0].y;
  const Wide dx2 = v[2].x - v[0].x, dy2 = v[2].y - v[0].y;
  const Wide det = s.edges.det;
  const Wide sign = det < 0 ? -1 : 1;
  const int sp = w.subpixel_bits;
  const int64_t half = int64_t{1} << (sp - 1);
  const Wide ref_x = Wide{s.box.x_lo} * (Wide{1} << sp) + half - v[0].x;
  const Wide ref_y = Wide{s.box.y_lo} * (Wide{1} << sp) + half - v[0].y;
  struct Exact {
    Wide at_ref, per_x, per_y;
  };
  fits_or_throw(ref_x, dw.diff_bits, "reference x offset");
  fits_or_throw(ref_y, dw.diff_bits, "reference y offset");
  const auto plane = [&](const std::array<Wide, 3>& a, int coef_bits, int ref_bits) {
    const Wide da1 = a[1] - a[0], da2 = a[2] - a[0];
    const Wide coef_x = sign * (da1 * dy2 - da2 * dy1);
    const Wide coef_y = sign * (da2 * dx1 - da1 * dx2);
    fits_or_throw(coef_x, coef_bits, "plane coefficient x");
    fits_or_throw(coef_y, coef_bits, "plane coefficient y");
    const Wide at_ref = sign * a[0] * det + coef_x * ref_x + coef_y * ref_y;
    fits_or_throw(at_ref, ref_bits, "plane value at the reference");
    return Exact{at_ref, coef_x * (Wide{1} << sp), coef_y * (Wide{1} << sp)};
  };
  const Exact eq = plane(q, dw.coef_q_bits, dw.exact_ref_q_bits);
  const Exact eu = plane(uq, dw.coef_uv_bits, dw.exact_ref_uv_bits);
  const Exact ev = plane(vq, dw.coef_uv_bits, dw.exact_ref_uv_bits);

  // Orientation: the constant-depth lines run along the axis in which q changes least.
  const Wide abs_qx = eq.per_x < 0 ? -eq.per_x : eq.per_x;
  const Wide abs_qy = eq.per_y < 0 ? -eq.per_y : eq.per_y;
  s.x_major = abs_qx <= abs_qy;
  const auto major = [&](const Exact& e) { return s.x_major ? e.per_x : e.per_y; };
  const auto minor = [&](const Exact& e) { return s.x_major ? e.per_y : e.per_x; };
  const int gf = w.g_frac;
  s.g = minor(eq) == 0 ? 0
                       : static_cast<int64_t>(divide_nearest(-major(eq) * (Wide{1} << gf), minor(eq)));

  // Shared shift: q * |det| peaks at a vertex, and after the shift it fits plane_bits.
  Wide q_peak = 0;
  for (size_t i = 0; i < 3; ++i) q_peak = std::max(q_peak, q[i] * (det < 0 ? -det : det));
  fits_unsigned_or_throw(q_peak, dw.peak_bits, "q |det|");
  fits_or_throw(s.g, dw.g_bits, "g");
  s.shift = fx::bit_length(q_peak) - w.plane_bits;
  fits_or_throw(s.shift, dw.shift_bits, "per-triangle shift");
  const int line_shift = log2_exact(s.density);
  const auto normalise = [&](const Exact& e, int ref_bits, int step_bits) {
    Plane p;
    p.at_ref = fx::shift_round(e.at_ref, s.shift, fx::Round::Nearest);
    p.per_major = fx::shift_round(major(e), s.shift, fx::Round::Nearest);
    p.per_minor = fx::shift_round(minor(e), s.shift, fx::Round::Nearest);
    p.per_line = fx::shift_round(minor(e), s.shift + line_shift, fx::Round::Nearest);
    fits_or_throw(p.at_ref, ref_bits, "normalised plane value at the reference");
    fits_or_throw(p.per_major, step_bits, "normalised plane step (major)");
    fits_or_throw(p.per_minor, step_bits, "normalised plane step (minor)");
    return p;
  };
  s.q = normalise(eq, dw.plane_ref_q_bits, dw.plane_step_q_bits);
  s.u = normalise(eu, dw.plane_ref_uv_bits, dw.plane_step_uv_bits);
  s.v = normalise(ev, dw.plane_ref_uv_bits, dw.plane_step_uv_bits);
  s.step_u = fx::shift_round(major(eu) * (Wide{1} << gf) + Wide{s.g} * minor(eu), s.shift + gf,
                             fx::Round::Nearest);
  s.step_v = fx::shift_round(major(ev) * (Wide{1} << gf) + Wide{s.g} * minor(ev), s.shift + gf,
                             fx::Round::Nearest);
  fits_or_throw(s.step_u, dw.step_uv_bits, "numerator of S.u");
  fits_or_throw(s.step_v, dw.step_uv_bits, "numerator of S.v");

  // Walk geometry along the chosen axes.
  s.major_lo = s.x_major ? s.box.x_lo : s.box.y_lo;
  s.major_count = s.x_major ? s.box.width() : s.box.height();
  s.minor_lo = s.x_major ? s.box.y_lo : s.box.x_lo;
  s.minor_hi = s.x_major ? s.box.y_hi : s.box.x_hi;

  // Lines the covered pixels use. The continuous line coordinate
  // kappa = (minor - minor_ref) - g (major - major_ref) is affine, so over the
  // triangle it lies between its values at the vertices; a pixel's line index is
  // within 1/2 of density * kappa. Values are scaled by 2^(subpixel_bits + g_frac).
  const Wide ref_major = s.x_major ? ref_x : ref_y;
  const Wide ref_minor = s.x_major ? ref_y : ref_x;
  Wide kappa_lo = 0, kappa_hi = 0;
  for (size_t i = 0; i < 3; ++i) {
    const Wide vertex_major = (s.x_major ? v[i].x - v[0].x : v[i].y - v[0].y) - ref_major;
    const Wide vertex_minor = (s.x_major ? v[i].y - v[0].y : v[i].x - v[0].x) - ref_minor;
    const Wide kappa = s.density * (vertex_minor * (Wide{1} << gf) - Wide{s.g} * vertex_major);
    fits_or_throw(kappa, dw.kappa_bits, "kappa");
    kappa_lo = i == 0 ? kappa : std::min(kappa_lo, kappa);
    kappa_hi = i == 0 ? kappa : std::max(kappa_hi, kappa);
  }
  const Wide scale = Wide{1} << (sp + gf);
  Wide line_lo = fx::ceil_div(2 * kappa_lo - scale, 2 * scale);
  Wide line_hi = fx::ceil_div(2 * kappa_hi + scale, 2 * scale) - 1;
  // The box bounds them too: line = density * minor_offset - round(density g o).
  const auto column_round = [&](int64_t offset) {
    return fx::floor_div(Wide{s.density} * s.g * offset + (Wide{1} << (gf - 1)), Wide{1} << gf);
  };
  const Wide round_first = 0, round_last = column_round(s.major_count - 1);
  line_lo = std::max(line_lo, -std::max(round_first, round_last));
  line_hi = std::min(line_hi, Wide{s.density} * (s.minor_hi - s.minor_lo) -
                                  std::min(round_first, round_last));
  if (line_lo <= line_hi) {
    fits_or_throw(line_lo, dw.line_bits, "first pixel line");
    fits_or_throw(line_hi, dw.line_bits, "last pixel line");
  }
  s.edge_trackers = edge_trackers(s.edges, s.x_major, s.major_lo, dw);
  s.pixel_line_lo = static_cast<int64_t>(line_lo);
  s.pixel_line_hi = static_cast<int64_t>(line_hi);
  return s;
}

Reciprocal reciprocal(Wide q, int recip_bits) {
  Reciprocal r;
  if (q <= 0) {
    r.out_of_range = true;
    q = 1;
  }
  r.exponent = fx::bit_length(q) - 1;
  // Mantissa of q in [1, 2) with recip_bits fraction bits, truncated.
  const Wide mantissa_q = r.exponent >= recip_bits ? q >> (r.exponent - recip_bits)
                                                   : q << (recip_bits - r.exponent);
  r.mantissa = static_cast<int64_t>((Wide{1} << (2 * recip_bits)) / mantissa_q);
  return r;
}

Wide quotient(Wide numerator, int numerator_frac, const Reciprocal& r, int recip_bits, const fx::Format& format,
              int guard_bits, bool* saturated) {
  const fx::Format operand{format.int_bits + 1, format.frac_bits + guard_bits, true};
  const Wide n = fx::narrow(numerator, numerator_frac + r.exponent, operand, fx::Round::Nearest,
                            fx::Overflow::Saturate, saturated);
  return fx::narrow(n * r.mantissa, recip_bits + operand.frac_bits, format, fx::Round::Nearest,
                    fx::Overflow::Saturate, saturated);
}

TableEntry fill_line(const Setup& s, int64_t line, const Widths& w) {
  const Wide q = s.q.at_ref + Wide{line} * s.q.per_line;
  const Wide u = s.u.at_ref + Wide{line} * s.u.per_line;
  const Wide v = s.v.at_ref + Wide{line} * s.v.per_line;
  fits_or_throw(q, s.fill_q_bits, "q on a table line");
  fits_or_throw(u, s.fill_uv_bits, "U on a table line");
  fits_or_throw(v, s.fill_uv_bits, "V on a table line");
  const Reciprocal r = reciprocal(q, w.recip_bits);
  // U / q: U carries uv_in_frac fraction bits of texels.
  bool saturated = false;
  const auto to = [&](Wide numerator, const fx::Format& format) {
    return static_cast<int64_t>(
        quotient(numerator, w.uv_in_frac, r, w.recip_bits, format, w.quotient_guard_bits, &saturated));
  };
  TableEntry e;
  e.t_u = to(u, w.t_format());
  e.t_v = to(v, w.t_format());
  e.s_u = to(s.step_u, w.s_format());
  e.s_v = to(s.step_v, w.s_format());
  e.flags = (saturated ? flag::kTableSaturated : 0) | (r.out_of_range ? flag::kDepthRange : 0);
  if (s.persp) {
    // eps = q_line / q_k: the plane's step per line times the same reciprocal.
    const fx::Format eps_format{w.eps_int, w.eps_frac, true};
    e.eps = static_cast<int64_t>(
        quotient(s.q.per_line, 0, r, w.recip_bits, eps_format, w.quotient_guard_bits, &e.eps_saturated));
    if (e.eps == eps_format.min_raw()) {  // keep -eps in the format
      e.eps += 1;
      e.eps_saturated = true;
    }
  }
  return e;
}

}  // namespace cdsim
