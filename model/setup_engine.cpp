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

// What a setup holds before stage D: the design's options, the edges and the box.
Setup setup_of(const SetupStageA& a, const Design& design) {
  Setup s;
  s.density = design.density;
  s.correction = design.correction;
  s.persp = design.persp;
  s.edges = a.edges;
  s.box = a.box;
  return s;
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

// Stage A: the edges, the box, 1/w aligned to the largest exponent, U = u q
// and V = v q, and the reference pixel centre relative to vertex 0.
SetupStageA setup_stage_a(const UnitTriangle& t, const Widths& w, const DerivedWidths& dw, int viewport_width,
                          int viewport_height) {
  SetupStageA a;
  a.edges = make_edges(t, w.subpixel_bits);
  a.box = bounding_box(t, w.subpixel_bits, viewport_width, viewport_height);
  if (a.edges.det == 0 || a.box.empty()) return a;
  a.empty = false;
  // Every intermediate is checked against the width the RTL gives it.
  for (const UnitVertex& vertex : t.vertex) {
    fits_or_throw(vertex.x, dw.coord_bits, "vertex x");
    fits_or_throw(vertex.y, dw.coord_bits, "vertex y");
    fits_or_throw(vertex.u, dw.uv_bits, "vertex u");
    fits_or_throw(vertex.v, dw.uv_bits, "vertex v");
  }
  fits_or_throw(a.edges.det, dw.det_bits, "det");
  for (size_t i = 0; i < 3; ++i) fits_or_throw(a.edges.c[i], dw.edge_c_bits, "edge c");

  // Per-triangle normalisation of 1/w: align the three mantissas to the largest
  // exponent. The shared exponent itself cancels in u = U/q and is dropped.
  a.q = normalised_q(t, w);
  for (size_t i = 0; i < 3; ++i) {
    if (a.q[i] == 0) a.flags |= flag::kDepthRange;
    a.uq[i] = a.q[i] * t.vertex[i].u;
    a.vq[i] = a.q[i] * t.vertex[i].v;
    fits_unsigned_or_throw(a.q[i], dw.q_vertex_bits, "vertex q");
    fits_or_throw(a.uq[i], dw.attr_uv_bits, "vertex U");
    fits_or_throw(a.vq[i], dw.attr_uv_bits, "vertex V");
  }
  const auto& v = t.vertex;
  const int sp = w.subpixel_bits;
  const int64_t half = int64_t{1} << (sp - 1);
  a.ref_x = Wide{a.box.x_lo} * (Wide{1} << sp) + half - v[0].x;
  a.ref_y = Wide{a.box.y_lo} * (Wide{1} << sp) + half - v[0].y;
  fits_or_throw(a.ref_x, dw.diff_bits, "reference x offset");
  fits_or_throw(a.ref_y, dw.diff_bits, "reference y offset");
  return a;
}

// Stage B: the plane coefficients of q, U and V, scaled by det and signed so
// that q |det| > 0, and the largest q |det|, which sets the shared shift.
SetupStageB setup_stage_b(const UnitTriangle& t, const SetupStageA& a, const DerivedWidths& dw) {
  SetupStageB b;
  const auto& v = t.vertex;
  const Wide dx1 = v[1].x - v[0].x, dy1 = v[1].y - v[0].y;
  const Wide dx2 = v[2].x - v[0].x, dy2 = v[2].y - v[0].y;
  const Wide det = a.edges.det;
  const Wide sign = det < 0 ? -1 : 1;
  const auto coefficients = [&](const std::array<Wide, 3>& attr, int coef_bits) {
    const Wide da1 = attr[1] - attr[0], da2 = attr[2] - attr[0];
    PlaneCoefficients c{sign * (da1 * dy2 - da2 * dy1), sign * (da2 * dx1 - da1 * dx2)};
    fits_or_throw(c.x, coef_bits, "plane coefficient x");
    fits_or_throw(c.y, coef_bits, "plane coefficient y");
    return c;
  };
  b.q = coefficients(a.q, dw.coef_q_bits);
  b.u = coefficients(a.uq, dw.coef_uv_bits);
  b.v = coefficients(a.vq, dw.coef_uv_bits);
  for (size_t i = 0; i < 3; ++i) {
    const Wide q_det = a.q[i] * (det < 0 ? -det : det);
    b.q_peak = std::max(b.q_peak, q_det);
    b.q_floor = i == 0 ? q_det : std::min(b.q_floor, q_det);
  }
  fits_unsigned_or_throw(b.q_peak, dw.peak_bits, "q |det|");
  return b;
}

// Stage C: the planes at the reference centre (exact), the orientation and
// the shared shift.
SetupStageC setup_stage_c(const SetupStageA& a, const SetupStageB& b, const Widths& w, const DerivedWidths& dw) {
  SetupStageC c;
  const Wide det = a.edges.det;
  const Wide sign = det < 0 ? -1 : 1;
  const auto at_ref = [&](Wide attr0, const PlaneCoefficients& p, int ref_bits) {
    const Wide value = sign * attr0 * det + p.x * a.ref_x + p.y * a.ref_y;
    fits_or_throw(value, ref_bits, "plane value at the reference");
    return value;
  };
  c.q_at_ref = at_ref(a.q[0], b.q, dw.exact_ref_q_bits);
  c.u_at_ref = at_ref(a.uq[0], b.u, dw.exact_ref_uv_bits);
  c.v_at_ref = at_ref(a.vq[0], b.v, dw.exact_ref_uv_bits);
  // Orientation: the constant-depth lines run along the axis in which q changes least.
  const Wide abs_qx = b.q.x < 0 ? -b.q.x : b.q.x;
  const Wide abs_qy = b.q.y < 0 ? -b.q.y : b.q.y;
  c.x_major = abs_qx <= abs_qy;
  // Shared shift: q * |det| peaks at a vertex, and after the shift it fits plane_bits.
  c.shift = fx::bit_length(b.q_peak) - w.plane_bits;
  fits_or_throw(c.shift, dw.shift_bits, "per-triangle shift");
  return c;
}

// The serial dividers, started in stage C and read in stage D: the slope g
// and, per edge, the span end at the first column and its step per column.
SetupDividers setup_dividers(const SetupStageA& a, const SetupStageB& b, const SetupStageC& c, const Widths& w,
                             const DerivedWidths& dw) {
  SetupDividers d;
  const Wide major = c.x_major ? b.q.x : b.q.y;
  const Wide minor = c.x_major ? b.q.y : b.q.x;
  d.g = minor == 0 ? 0 : static_cast<int64_t>(divide_nearest(-major * (Wide{1} << w.g_frac), minor));
  fits_or_throw(d.g, dw.g_bits, "g");
  d.edge_trackers = edge_trackers(a.edges, c.x_major, c.x_major ? a.box.x_lo : a.box.y_lo, dw);
  return d;
}

// Stage D: the normalised planes, the numerators of S, the walk's axes and
// the range of lines the covered pixels use.
Setup setup_stage_d(const UnitTriangle& t, const SetupStageA& a, const SetupStageB& b, const SetupStageC& c,
                    const SetupDividers& dividers, const Design& design, const Widths& w, const DerivedWidths& dw) {
  Setup s = setup_of(a, design);
  s.empty = false;
  s.flags = a.flags;
  s.fill_q_bits = dw.fill_q_bits;
  s.fill_uv_bits = dw.fill_uv_bits;
  s.pixel_q_bits = dw.pixel_q_bits;
  s.pixel_uv_bits = dw.pixel_uv_bits;
  s.x_major = c.x_major;
  s.g = dividers.g;
  s.shift = c.shift;
  s.edge_trackers = dividers.edge_trackers;

  const int sp = w.subpixel_bits;
  const int gf = w.g_frac;
  const auto major = [&](const PlaneCoefficients& p) { return (s.x_major ? p.x : p.y) * (Wide{1} << sp); };
  const auto minor = [&](const PlaneCoefficients& p) { return (s.x_major ? p.y : p.x) * (Wide{1} << sp); };
  const int line_shift = log2_exact(s.density);
  const auto normalise = [&](Wide at_ref, const PlaneCoefficients& p, int ref_bits, int step_bits) {
    Plane n;
    n.at_ref = fx::shift_round(at_ref, s.shift, fx::Round::Nearest);
    n.per_major = fx::shift_round(major(p), s.shift, fx::Round::Nearest);
    n.per_minor = fx::shift_round(minor(p), s.shift, fx::Round::Nearest);
    n.per_line = fx::shift_round(minor(p), s.shift + line_shift, fx::Round::Nearest);
    fits_or_throw(n.at_ref, ref_bits, "normalised plane value at the reference");
    fits_or_throw(n.per_major, step_bits, "normalised plane step (major)");
    fits_or_throw(n.per_minor, step_bits, "normalised plane step (minor)");
    return n;
  };
  s.q = normalise(c.q_at_ref, b.q, dw.plane_ref_q_bits, dw.plane_step_q_bits);
  s.u = normalise(c.u_at_ref, b.u, dw.plane_ref_uv_bits, dw.plane_step_uv_bits);
  s.v = normalise(c.v_at_ref, b.v, dw.plane_ref_uv_bits, dw.plane_step_uv_bits);
  s.step_u = fx::shift_round(major(b.u) * (Wide{1} << gf) + Wide{s.g} * minor(b.u), s.shift + gf,
                             fx::Round::Nearest);
  s.step_v = fx::shift_round(major(b.v) * (Wide{1} << gf) + Wide{s.g} * minor(b.v), s.shift + gf,
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
  const auto& v = t.vertex;
  const Wide ref_major = s.x_major ? a.ref_x : a.ref_y;
  const Wide ref_minor = s.x_major ? a.ref_y : a.ref_x;
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
  // The line phase. Without it, the farthest line a pixel can use lies d0
  // gaps beyond the far vertex (the next line at or past its kappa), and the
  // horizon h = q_floor m / |q per minor pixel| gaps beyond it. When that line
  // may lie within half a gap of the horizon or past it (h < d0 + 1/2, d0
  // bounded in quarters of a gap so that the test is a comparator and a
  // three-bit multiple), move the lines by phi in [0, 1) gaps so that one lies
  // at the far vertex or up to 2^-line_phase_bits gaps beyond it: every
  // covered pixel and its correction neighbour then lie on the near side.
  const int pb = w.line_phase_frac();
  s.line_phase_bits = pb;
  const Wide q_minor = minor(b.q);
  const Wide abs_minor = q_minor < 0 ? -q_minor : q_minor;  // |q per minor pixel|
  // With g = 0 every pixel lies on its own line (t = 0) and reads no
  // neighbour, so no line past the horizon is ever read: no phase.
  if (pb > 0 && design.kind == Design::Kind::ConstantDepth && q_minor != 0 && s.g != 0) {
    const Wide unit = Wide{1} << (sp + gf - pb);  // 2^-pb gaps in kappa's units
    const Wide mask = (Wide{1} << pb) - 1;
    // q grows with kappa when it grows along the minor axis: the far vertex
    // has the least kappa, and the lines at or below it are beyond it.
    const bool far_low = q_minor > 0;
    const Wide phi = (far_low ? fx::floor_div(kappa_lo, unit) : fx::ceil_div(kappa_hi, unit)) & mask;
    // d0 < (beyond + 1) 2^-pb, and < (quarters + 1) / 4.
    const Wide beyond = far_low ? phi : (phi == 0 ? 0 : (Wide{1} << pb) - phi);
    const Wide quarters = (4 * beyond + 3) >> pb;  // the least with (beyond + 1) 2^-pb <= (quarters + 1) / 4
    if (4 * b.q_floor * s.density < abs_minor * (quarters + 3)) s.line_phase = static_cast<int64_t>(phi);
  }
  // The divide fallback: the far vertex within 2^fallback_gaps_log2 gaps of
  // the horizon, q_floor m < |q_minor| 2^k (a shift and a comparator).
  if (design.fallback && q_minor != 0 && s.g != 0)
    s.fallback = b.q_floor * s.density < abs_minor * (Wide{1} << w.fallback_gaps_log2);
  const Wide phase = Wide{s.line_phase} * (Wide{1} << (sp + gf - pb));  // in kappa's units
  Wide line_lo = fx::ceil_div(2 * (kappa_lo - phase) - scale, 2 * scale);
  Wide line_hi = fx::ceil_div(2 * (kappa_hi - phase) + scale, 2 * scale) - 1;
  // The box bounds them too: line = density * minor_offset - round(density g o + phi).
  const Wide phase_g = Wide{s.line_phase} * (Wide{1} << (gf - pb));  // in g_frac bits
  const auto column_round = [&](int64_t offset) {
    return fx::floor_div(Wide{s.density} * s.g * offset + phase_g + (Wide{1} << (gf - 1)), Wide{1} << gf);
  };
  const Wide round_first = column_round(0), round_last = column_round(s.major_count - 1);
  line_lo = std::max(line_lo, -std::max(round_first, round_last));
  line_hi = std::min(line_hi, Wide{s.density} * (s.minor_hi - s.minor_lo) -
                                  std::min(round_first, round_last));
  if (line_lo <= line_hi) {
    fits_or_throw(line_lo, dw.line_bits, "first pixel line");
    fits_or_throw(line_hi, dw.line_bits, "last pixel line");
  }
  s.pixel_line_lo = static_cast<int64_t>(line_lo);
  s.pixel_line_hi = static_cast<int64_t>(line_hi);
  return s;
}

Setup setup_engine(const UnitTriangle& t, const Design& design, const Widths& w, const DerivedWidths& dw,
                   int viewport_width, int viewport_height) {
  const SetupStageA a = setup_stage_a(t, w, dw, viewport_width, viewport_height);
  if (a.empty) return setup_of(a, design);
  const SetupStageB b = setup_stage_b(t, a, dw);
  const SetupStageC c = setup_stage_c(a, b, w, dw);
  const SetupDividers dividers = setup_dividers(a, b, c, w, dw);
  return setup_stage_d(t, a, b, c, dividers, design, w, dw);
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

Wide plane_on_line(const Setup& s, const Plane& plane, int64_t line) {
  const int pb = s.line_phase_bits;
  return plane.at_ref +
         fx::shift_round((Wide{line} * (Wide{1} << pb) + s.line_phase) * plane.per_line, pb, fx::Round::Nearest);
}

TableEntry fill_line(const Setup& s, int64_t line, const Widths& w) {
  const Wide q = plane_on_line(s, s.q, line);
  const Wide u = plane_on_line(s, s.u, line);
  const Wide v = plane_on_line(s, s.v, line);
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
