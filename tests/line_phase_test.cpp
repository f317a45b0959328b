// The line phase (issue 41, docs/robustness.md "The line phase"): a
// constant-depth triangle whose farthest line would lie within half a gap of
// its horizon (or past it) has its lines moved so that one lies at its far
// vertex or less than 2^-line_phase_bits gaps beyond it. Checked against the far
// vertex's line coordinate and the horizon distance computed here in long
// double from the snapped vertices, and by what the phase is for: no line a
// pixel uses lies past the horizon.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace cdsim {
namespace {

constexpr int kWidth = 256, kHeight = 256;

// A small triangle whose nearest vertex to its horizon lies `gap` pixels from
// it along the minor axis; the horizon runs at slope `tilt`; transposed when
// `y_major` (the same geometry with x and y swapped).
ScreenTriangle near_horizon(std::mt19937_64& rng, double gap, double tilt, bool y_major) {
  std::uniform_real_distribution<double> at(40, 200), offset(-6, 6), height(0.01, 3), tex(-300, 300);
  const double x0 = at(rng), y0 = at(rng);
  std::array<std::array<double, 2>, 3> p = {{{x0, y0}, {x0 + offset(rng), y0 + height(rng)},
                                             {x0 + offset(rng), y0 + height(rng)}}};
  double horizon = 1e300;
  for (const auto& v : p) horizon = std::min(horizon, v[1] - tilt * (v[0] - x0));
  horizon -= gap;
  std::array<std::array<double, 5>, 3> v{};
  for (size_t i = 0; i < 3; ++i) {
    const double q = 0.02 * (p[i][1] - horizon - tilt * (p[i][0] - x0));
    v[i] = {p[i][0], p[i][1], 1.0 / q, tex(rng), tex(rng)};
    if (y_major) std::swap(v[i][0], v[i][1]);
  }
  return testing::screen_triangle(v);
}

struct Oracle {
  long double horizon_gaps = 0;  // the far vertex's distance to the horizon, in line gaps
  long double unphased_beyond = 0;  // from it to the farthest line a pixel can use with phi = 0
  long double far_kappa = 0;     // its line coordinate (gaps from the reference centre)
  bool far_is_low = true;        // q grows with kappa: the far vertex has the least kappa
};

// From the snapped vertices, the quantised g the unit uses and q = 1/w.
Oracle oracle(const ScreenTriangle& screen, const UnitTriangle& unit, const Setup& s, const Widths& w) {
  using LD = long double;
  std::array<LD, 3> major{}, minor{}, q{};
  for (size_t i = 0; i < 3; ++i) {
    const LD x = snapped_pixels(unit.vertex[i].x, w.subpixel_bits);
    const LD y = snapped_pixels(unit.vertex[i].y, w.subpixel_bits);
    major[i] = s.x_major ? x : y;
    minor[i] = s.x_major ? y : x;
    q[i] = 1.0L / screen.vertex[i].w;
  }
  const LD det = (major[1] - major[0]) * (minor[2] - minor[0]) - (major[2] - major[0]) * (minor[1] - minor[0]);
  const LD dq_dminor = ((q[2] - q[0]) * (major[1] - major[0]) - (q[1] - q[0]) * (major[2] - major[0])) / det;
  const size_t far = static_cast<size_t>(std::min_element(q.begin(), q.end()) - q.begin());
  const LD g = std::ldexp(static_cast<LD>(s.g), -w.g_frac);
  const LD ref_major = static_cast<LD>(s.major_lo) + 0.5L, ref_minor = static_cast<LD>(s.minor_lo) + 0.5L;
  Oracle o;
  o.horizon_gaps = q[far] / std::fabs(dq_dminor) * s.density;
  o.far_kappa = s.density * ((minor[far] - ref_minor) - g * (major[far] - ref_major));
  o.far_is_low = dq_dminor > 0;
  o.unphased_beyond = o.far_is_low ? o.far_kappa - std::floor(o.far_kappa) : std::ceil(o.far_kappa) - o.far_kappa;
  return o;
}

TEST(LinePhase, OneLineLiesAtTheFarVertexOrJustBeyondIt) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> gap(0.02, 7), tilt(-0.95, 0.95);
  int phased = 0, plain = 0;
  for (const char* name : {"cd-linear", "cd-dense2-linear", "cd-persp"}) {
    const Design& design = find_design(name);
    for (const int bits : {1, 6, 12}) {
      Widths w;
      w.line_phase_bits = bits;
      for (int n = 0; n < 300; ++n) {
        const ScreenTriangle screen = near_horizon(rng, gap(rng), tilt(rng), n % 2 == 1);
        const UnitTriangle unit = to_unit(screen, w, 0);
        const ::cdsim::Setup s = setup_engine(unit, design, w, kWidth, kHeight);
        if (s.empty) continue;
        const Oracle o = oracle(screen, unit, s, w);
        // The phase is taken where the farthest line without it would lie
        // within half a gap of the horizon (or past it), and not where it
        // lies farther than that by more than the unit's bound on that
        // line's distance adds: 2^-bits, and a quarter of a gap.
        const long double margin = o.horizon_gaps - o.unphased_beyond;
        const long double slack = 0.5L + std::max(std::ldexp(1.0L, -bits), 0.25L);
        if (std::fabs(margin - 0.5L) < 1e-3L || std::fabs(margin - slack) < 1e-3L) continue;
        SCOPED_TRACE(::testing::Message() << name << " bits " << bits << " triangle " << n << " horizon "
                                          << static_cast<double>(o.horizon_gaps) << " gaps, farthest line "
                                          << static_cast<double>(o.unphased_beyond) << " beyond");
        if (margin > slack || s.g == 0) {
          EXPECT_EQ(s.line_phase, 0);
          ++plain;
          continue;
        }
        if (margin >= 0.5L) continue;  // either way
        EXPECT_NE(s.g, 0);
        ++phased;
        // Lines lie at k + phi: the far vertex's kappa less phi is within
        // 2^-bits of a whole number, on the triangle's side of it.
        const long double phi = std::ldexp(static_cast<long double>(s.line_phase), -bits);
        const long double from_line = o.far_kappa - phi;
        const long double beyond = o.far_is_low ? from_line - std::floor(from_line) : std::ceil(from_line) - from_line;
        EXPECT_LT(beyond, std::ldexp(1.0L, -bits) + 1e-9L);
        EXPECT_GE(s.line_phase, 0);
        EXPECT_LT(s.line_phase, int64_t{1} << bits);
      }
    }
  }
  EXPECT_GT(phased, 200);
  EXPECT_GT(plain, 100);
}

// What the phase is for: no pixel's line or correction neighbour past the
// horizon (depth_range, neighbour_dropped), where without it there are some.
TEST(LinePhase, NoLineAPixelUsesLiesPastTheHorizon) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> gap(0.02, 1.5), tilt(-0.95, 0.95);
  std::vector<ScreenTriangle> triangles;
  for (int n = 0; n < 400; ++n) triangles.push_back(near_horizon(rng, gap(rng), tilt(rng), n % 2 == 1));
  const uint32_t past = flag::kDepthRange | flag::kNeighbourDropped;
  for (const char* name : {"cd-linear", "cd-persp"}) {
    int64_t flagged_without = 0, pixels = 0;
    for (const int bits : {0, 6}) {
      Widths w;
      w.line_phase_bits = bits;
      for (size_t n = 0; n < triangles.size(); ++n) {
        TriangleRecord record;
        const auto fragments =
            testing::run_unit(find_design(name), w, kWidth, kHeight, to_unit(triangles[n], w, n), &record);
        if (bits == 0) {
          flagged_without += (record.flags & past) != 0;
          continue;
        }
        pixels += static_cast<int64_t>(fragments.size());
        for (const Fragment& f : fragments)
          EXPECT_EQ(f.flags & past, 0u) << name << " triangle " << n << " pixel " << f.x << "," << f.y;
      }
    }
    EXPECT_GT(flagged_without, 10) << name << ": the triangles should need the phase";
    EXPECT_GT(pixels, 1000) << name;
  }
}

// The divide fallback (cd-linear-div, cd-persp-div; docs/robustness.md): a
// triangle with g != 0 whose far vertex lies within 2^fallback_gaps_log2 line
// gaps of its horizon is walked by divide's datapath, bit for bit divide's
// pixels; the others by the table, as their design without the fallback.
TEST(DivideFallback, TakenWhereTheFarVertexLiesWithinItsBound) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> gap(0.02, 80), tilt(-0.95, 0.95);
  int taken = 0, left = 0;
  for (const auto& [name, plain] : {std::pair{"cd-linear-div", "cd-linear"}, std::pair{"cd-persp-div", "cd-persp"}}) {
    for (const int k : {0, 3, 5}) {
      Widths w;
      w.fallback_gaps_log2 = k;
      for (int n = 0; n < 150; ++n) {
        const ScreenTriangle screen = near_horizon(rng, gap(rng), tilt(rng), n % 2 == 1);
        const UnitTriangle unit = to_unit(screen, w, 0);
        const ::cdsim::Setup s = setup_engine(unit, find_design(name), w, kWidth, kHeight);
        if (s.empty) continue;
        EXPECT_FALSE(setup_engine(unit, find_design(plain), w, kWidth, kHeight).fallback) << plain;
        const long double bound = std::ldexp(1.0L, k);
        const long double h = oracle(screen, unit, s, w).horizon_gaps;
        if (std::fabs(h / bound - 1) < 1e-3L) continue;  // q's rounding decides
        SCOPED_TRACE(::testing::Message() << name << " k " << k << " triangle " << n << " horizon "
                                          << static_cast<double>(h) << " gaps, g " << s.g);
        EXPECT_EQ(s.fallback, s.g != 0 && h < bound);
        TriangleRecord record;
        const auto fragments = testing::run_unit(find_design(name), w, kWidth, kHeight, unit, &record);
        const auto expected =
            testing::run_unit(find_design(s.fallback ? "divide" : plain), w, kWidth, kHeight, unit, nullptr);
        ASSERT_EQ(fragments.size(), expected.size());
        for (size_t i = 0; i < fragments.size(); ++i) {
          EXPECT_EQ(fragments[i].u, expected[i].u) << "pixel " << i;
          EXPECT_EQ(fragments[i].v, expected[i].v) << "pixel " << i;
          EXPECT_EQ(fragments[i].flags, expected[i].flags) << "pixel " << i;
        }
        EXPECT_EQ(record.fallback, s.fallback);
        (s.fallback ? taken : left) += 1;
      }
    }
  }
  EXPECT_GT(taken, 100);
  EXPECT_GT(left, 100);
}

}  // namespace
}  // namespace cdsim
