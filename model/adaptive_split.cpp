#include "adaptive_split.hpp"

#include <array>

#include "pixel_coverage.hpp"
#include "design.hpp"
#include "fixed.hpp"
#include "setup_engine.hpp"

namespace cdsim {

using fx::Wide;

namespace {

// A vertex in the split engine. x, y carry adapt_depth more subpixel bits, q,
// U = u q and V = v q are scaled by 2^adapt_depth: a node at depth d holds
// values with adapt_depth - d low zero bits, so its midpoints are exact. u, v
// are at the leaf's uv_in_frac: exact at the triangle's vertices, rounded at
// midpoints.
struct SplitVertex {
  int64_t x = 0, y = 0;
  Wide q = 0, big_u = 0, big_v = 0;
  int64_t u = 0, v = 0;
};

struct Node {
  std::array<SplitVertex, 3> vertex;
  int depth = 0;
};

UnitTriangle to_triangle(const Node& node) {
  UnitTriangle t;
  for (size_t i = 0; i < 3; ++i) {
    const SplitVertex& s = node.vertex[i];
    UnitVertex& v = t.vertex[i];
    v.x = s.x;
    v.y = s.y;
    v.u = s.u;
    v.v = s.v;
    // The affine unit uses 1/w only for its depth-range flag: q as binary32,
    // its mantissa truncated (a leading-one detector and a shift), 0 as 0.
    if (s.q > 0) {
      const int exponent = fx::bit_length(s.q) - 1;
      const Wide mantissa = exponent >= 23 ? s.q >> (exponent - 23) : s.q << (23 - exponent);
      v.q_float = (static_cast<uint32_t>(exponent + 127) << 23) | (static_cast<uint32_t>(mantissa) & 0x7fffffu);
    }
  }
  return t;
}

}  // namespace

AdaptiveSplit adaptive_split(const UnitTriangle& triangle, const Widths& w, int viewport_width,
                             int viewport_height) {
  const Widths leaf_widths = adaptive_leaf_widths(w);
  const int depth_limit = w.adapt_depth;
  const int extra = w.adapt_uv_extra;
  const fx::Format uv_format{16, leaf_widths.uv_in_frac, true};  // |u| < 2^15 texels, as at the input
  // |u_P + u_Q - 2 u_M| > 2 * 2^-adapt_bound_frac texels, compared as integers.
  const auto misses = [&](int64_t a, int64_t b, int64_t middle) {
    const Wide error = Wide{a} + b - 2 * Wide{middle};
    const Wide magnitude = error < 0 ? -error : error;
    return (magnitude << w.adapt_bound_frac) > (Wide{1} << (leaf_widths.uv_in_frac + 1));
  };

  AdaptiveSplit out;
  const std::array<Wide, 3> q = normalised_q(triangle, w);
  Node root;
  for (size_t i = 0; i < 3; ++i) {
    const UnitVertex& in = triangle.vertex[i];
    SplitVertex& s = root.vertex[i];
    s.x = in.x * (int64_t{1} << depth_limit);
    s.y = in.y * (int64_t{1} << depth_limit);
    const Wide scale = Wide{1} << depth_limit;  // multiplied: U and V may be negative
    s.q = q[i] * scale;
    s.big_u = q[i] * in.u * scale;
    s.big_v = q[i] * in.v * scale;
    s.u = in.u * (int64_t{1} << extra);
    s.v = in.v * (int64_t{1} << extra);
    if (q[i] == 0) out.flags |= flag::kDepthRange;
  }

  std::vector<Node> stack = {root};
  SplitEngineWork work;  // the split engine's since the last leaf was accepted
  const auto emit = [&](const Node& node) {
    out.leaves.push_back({to_triangle(node), node.depth, work});
    work = {};
  };
  while (!stack.empty()) {
    const Node node = stack.back();
    stack.pop_back();
    const UnitTriangle t = to_triangle(node);
    const bool nothing = make_edges(t, leaf_widths.subpixel_bits).det == 0 ||
                         bounding_box(t, leaf_widths.subpixel_bits, viewport_width, viewport_height).empty();
    if (nothing && node.depth > 0) {
      // A sub-triangle's box holds no pixel centre: nothing to send.
      ++work.drops;
      ++out.dropped;
      continue;
    }
    if (nothing || node.depth == depth_limit) {
      emit(node);
      continue;
    }
    // Midpoint j lies on the edge opposite vertex j, between vertices j+1 and j+2.
    ++out.evaluations;
    ++work.evaluations;
    std::array<SplitVertex, 3> middle{};
    bool split = false;
    for (size_t j = 0; j < 3; ++j) {
      const SplitVertex& a = node.vertex[(j + 1) % 3];
      const SplitVertex& b = node.vertex[(j + 2) % 3];
      SplitVertex& m = middle[j];
      m.x = (a.x + b.x) / 2;
      m.y = (a.y + b.y) / 2;
      m.q = (a.q + b.q) / 2;
      m.big_u = (a.big_u + b.big_u) / 2;
      m.big_v = (a.big_v + b.big_v) / 2;
      const Reciprocal r = reciprocal(m.q, w.recip_bits);
      if (r.out_of_range) out.flags |= flag::kDepthRange;
      bool saturated = false;
      m.u = static_cast<int64_t>(
          quotient(m.big_u, w.uv_in_frac, r, w.recip_bits, uv_format, w.quotient_guard_bits, &saturated));
      m.v = static_cast<int64_t>(
          quotient(m.big_v, w.uv_in_frac, r, w.recip_bits, uv_format, w.quotient_guard_bits, &saturated));
      if (saturated) out.flags |= flag::kOutputSaturated;
      split = split || misses(a.u, b.u, m.u) || misses(a.v, b.v, m.v);
    }
    if (!split) {
      emit(node);
      continue;
    }
    ++out.splits;
    const auto& v = node.vertex;
    const int d = node.depth + 1;
    // Pushed in reverse, so that they are taken A's corner, B's, C's, then the middle.
    stack.push_back({{middle[2], middle[0], middle[1]}, d});
    stack.push_back({{middle[1], middle[0], v[2]}, d});
    stack.push_back({{middle[2], v[1], middle[0]}, d});
    stack.push_back({{v[0], middle[2], middle[1]}, d});
  }
  if (out.leaves.empty()) {
    // Every sub-triangle was dropped, so the triangle covers no pixel centre
    // (its leaves would tile it): it goes to the unit whole, for its record.
    emit(root);
  }
  out.tail = work;
  return out;
}

}  // namespace cdsim
