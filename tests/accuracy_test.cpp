// With wide widths each design computes its algorithm without visible
// arithmetic error: constant-depth designs agree with an ideal long-double
// version of the same algorithm, and `divide` with the exact reference.
#include <gtest/gtest.h>

#include "affine_datapath.hpp"
#include "test_support.hpp"

namespace cdsim {
namespace {

constexpr int kWidth = 160, kHeight = 120;

TEST(Accuracy, WideWidthsMatchTheIdealAlgorithmForEveryConstantDepthDesign) {
  const Widths w = testing::wide_widths();
  std::mt19937_64 rng(2024);
  int orientations[2] = {0, 0};
  for (const Design& d : all_designs()) {
    if (d.kind != Design::Kind::ConstantDepth) continue;
    long double worst = 0;
    int64_t compared = 0;
    for (int n = 0; n < 200; ++n) {
      const ScreenTriangle s = testing::random_triangle(rng, kWidth, kHeight, 50.0, 1000.0);
      const UnitTriangle t = to_unit(s, w, size_t(n));
      const ::cdsim::Setup setup = setup_engine(t, d, w, kWidth, kHeight);
      if (setup.empty) continue;
      // The divide fallback's triangles are divide's, bit for bit
      // (DivideFallback.TakenWhereTheFarVertexLiesWithinItsBound).
      if (setup.fallback) continue;
      ++orientations[setup.x_major ? 0 : 1];
      const testing::IdealConstantDepth ideal(t, setup, w);
      for (const Fragment& f : testing::run_unit(d, w, kWidth, kHeight, t)) {
        if (f.flags != 0) continue;  // a flagged pixel is reported, not silently wrong
        const testing::IdealValue i = ideal.at_pixel(f.x, f.y);
        const long double lsb = std::ldexp(1.0L, -w.out_frac);
        const long double e = std::max(std::fabs(f.u * lsb - i.u), std::fabs(f.v * lsb - i.v));
        worst = std::max(worst, e);
        ++compared;
        // Datapath error: a few output LSBs, plus half an LSB of the correction
        // weight times the gap between the two lines it blends.
        // cd-persp's weight adds x, r and c e rounded at persp_frac bits
        // (tests/persp_test.cpp bounds them by 16 LSBs).
        const long double tolerance =
            4 * lsb + i.neighbour_gap * (std::ldexp(1.0L, -w.d_frac - 1) +
                                         (d.persp ? std::ldexp(1.0L, 4 - w.persp_frac) : 0));
        ASSERT_LT(e, tolerance) << d.name << " triangle " << n << " pixel (" << f.x << ", " << f.y
                            << ") got " << double(f.u * lsb) << " ideal " << double(i.u);
      }
    }
    EXPECT_GT(compared, 10000) << d.name;
    RecordProperty(d.name + "_worst_vs_ideal", std::to_string(double(worst)));
  }
  EXPECT_GT(orientations[0], 0) << "no x-major triangle was drawn";
  EXPECT_GT(orientations[1], 0) << "no y-major triangle was drawn";
}

TEST(Accuracy, DivideAtWideWidthsMatchesTheExactReference) {
  const Widths w = testing::wide_widths();
  const Design& divide = find_design("divide");
  std::mt19937_64 rng(77);
  for (int n = 0; n < 200; ++n) {
    const ScreenTriangle s = testing::random_triangle(rng, kWidth, kHeight, 50.0, 1000.0);
    const UnitTriangle t = to_unit(s, w, size_t(n));
    const ExactReference exact(s, t, w.subpixel_bits);
    for (const Fragment& f : testing::run_unit(divide, w, kWidth, kHeight, t)) {
      const ExactSample x = exact.at_pixel(f.x, f.y);
      const long double lsb = std::ldexp(1.0L, -w.out_frac);
      // The unit's inputs are 1/w in binary32 and u, v with 12 fraction bits:
      // their quantisation, not the datapath, sets this bound.
      ASSERT_NEAR(double(f.u * lsb), double(x.u), 2e-3) << "triangle " << n;
      ASSERT_NEAR(double(f.v * lsb), double(x.v), 2e-3) << "triangle " << n;
    }
  }
}

TEST(Accuracy, LinearCorrectionBeatsNoCorrectionOnRandomTriangles) {
  const Widths w = testing::wide_widths();
  std::mt19937_64 rng(5);
  double error[2] = {0, 0};
  const char* names[2] = {"cd-none", "cd-linear"};
  std::vector<ScreenTriangle> triangles;
  for (int n = 0; n < 100; ++n) triangles.push_back(testing::random_triangle(rng, kWidth, kHeight, 20.0, 500.0));
  for (int k = 0; k < 2; ++k) {
    for (size_t n = 0; n < triangles.size(); ++n) {
      const UnitTriangle t = to_unit(triangles[n], w, n);
      const ExactReference exact(triangles[n], t, w.subpixel_bits);
      for (const Fragment& f : testing::run_unit(find_design(names[k]), w, kWidth, kHeight, t)) {
        const ExactSample x = exact.at_pixel(f.x, f.y);
        error[k] += double(std::fabs(std::ldexp(static_cast<long double>(f.u), -w.out_frac) - x.u));
      }
    }
  }
  EXPECT_GT(error[0], 10.0 * error[1]);
}

}  // namespace
}  // namespace cdsim

namespace cdsim {
namespace {

TEST(Accuracy, KimAtWideWidthsMatchesTheExactReference) {
  Widths w = testing::wide_widths();
  w.kim_frac = 16;
  std::mt19937_64 rng(31);
  for (const char* name : {"kim-iter", "kim-pipe"}) {
    for (int n = 0; n < 100; ++n) {
      const ScreenTriangle s = testing::random_triangle(rng, kWidth, kHeight, 50.0, 1000.0);
      const UnitTriangle t = to_unit(s, w, size_t(n));
      const ExactReference exact(s, t, w.subpixel_bits);
      for (const Fragment& f : testing::run_unit(find_design(name), w, kWidth, kHeight, t)) {
        const ExactSample x = exact.at_pixel(f.x, f.y);
        const long double lsb = std::ldexp(1.0L, -w.out_frac);
        // Input quantisation (as for divide) plus the truncated 16-bit fraction.
        ASSERT_NEAR(double(f.u * lsb), double(x.u), 2e-3) << name << " triangle " << n;
        ASSERT_NEAR(double(f.v * lsb), double(x.v), 2e-3) << name << " triangle " << n;
      }
    }
  }
}

TEST(Accuracy, SubdividedAffineIsExactAtSegmentEndsAndAffineBetween) {
  // affine-sub8 equals divide at the span's first pixel and every 8th pixel.
  const Widths w = testing::wide_widths();
  std::mt19937_64 rng(8);
  for (int n = 0; n < 50; ++n) {
    const ScreenTriangle s = testing::random_triangle(rng, kWidth, kHeight, 20.0, 500.0);
    const UnitTriangle t = to_unit(s, w, size_t(n));
    const auto sub = testing::run_unit(find_design("affine-sub8"), w, kWidth, kHeight, t);
    const auto exact = testing::run_unit(find_design("divide"), w, kWidth, kHeight, t);
    ASSERT_EQ(sub.size(), exact.size());
    const ::cdsim::Setup setup = setup_engine(t, find_design("divide"), w, kWidth, kHeight);
    int64_t span_start = -1, previous_major = -1;
    for (size_t i = 0; i < sub.size(); ++i) {
      const int64_t major = setup.x_major ? sub[i].x : sub[i].y;
      const int64_t minor = setup.x_major ? sub[i].y : sub[i].x;
      if (major != previous_major) span_start = minor, previous_major = major;
      if ((minor - span_start) % 8 != 0) continue;
      // Both round the same exact value, from s_frac and from the reciprocal product.
      EXPECT_LE(std::abs(sub[i].u - exact[i].u), 1) << "triangle " << n << " pixel " << i;
      EXPECT_LE(std::abs(sub[i].v - exact[i].v), 1) << "triangle " << n << " pixel " << i;
    }
  }
}

TEST(Accuracy, QuadraticSegmentIsTheLagrangeQuadraticRoundedOnce) {
  // The oracle: Lagrange's form through (0, a), (L/2, m), (L, b) times L^2,
  //   a (L - 2p)(L - p) + 4 m p (L - p) + b p (2p - L),
  // rounded to nearest (ties up) from s_frac + 2 log2 L fraction bits. The
  // model evaluates the forward-difference form instead.
  const Widths w = testing::wide_widths();
  std::mt19937_64 rng(42);
  const int64_t range = int64_t{1} << (w.out_int + w.s_frac - 3);  // no saturation
  std::uniform_int_distribution<int64_t> value(-range, range);
  for (int64_t length = 1; length <= 64; length *= 2) {
    for (int n = 0; n < 200; ++n) {
      CorrectedValue a, m, b;
      a.u = value(rng), m.u = value(rng), b.u = value(rng);
      a.v = value(rng) / 1024, m.v = a.v + value(rng) / 4096, b.v = m.v + value(rng) / 4096;
      int log2_length_squared = 0;
      while ((int64_t{1} << log2_length_squared) < length * length) ++log2_length_squared;
      const int shift = log2_length_squared + w.s_frac - w.out_frac;
      for (int64_t p = 0; p <= length; ++p) {
        const auto lagrange = [&](int64_t fa, int64_t fm, int64_t fb) {
          const fx::Wide L = length;
          const fx::Wide scaled = fx::Wide{fa} * (L - 2 * p) * (L - p) + fx::Wide{fm} * 4 * p * (L - p) +
                                  fx::Wide{fb} * p * (2 * p - L);
          return static_cast<int64_t>((scaled + (fx::Wide{1} << (shift - 1))) >> shift);
        };
        const CorrectedValue q = quadratic_segment(a, m, b, length, p, w);
        ASSERT_FALSE(q.saturated);
        ASSERT_EQ(q.u, lagrange(a.u, m.u, b.u)) << "length " << length << " position " << p;
        ASSERT_EQ(q.v, lagrange(a.v, m.v, b.v)) << "length " << length << " position " << p;
      }
    }
  }
}

TEST(Accuracy, QuadraticSubdivisionIsExactAtItsPoints) {
  // quad-sub16 equals divide at each segment's start, middle and end. The
  // segments, written independently here: 16 pixels while 16 remain, then the
  // remainder's binary digits from the highest (11 = 8 + 2 + 1).
  const Widths w = testing::wide_widths();
  std::mt19937_64 rng(16);
  int64_t compared = 0;
  for (int n = 0; n < 50; ++n) {
    const ScreenTriangle s = testing::random_triangle(rng, kWidth, kHeight, 20.0, 500.0);
    const UnitTriangle t = to_unit(s, w, size_t(n));
    const auto quad = testing::run_unit(find_design("quad-sub16"), w, kWidth, kHeight, t);
    const auto exact = testing::run_unit(find_design("divide"), w, kWidth, kHeight, t);
    ASSERT_EQ(quad.size(), exact.size());
    const ::cdsim::Setup setup = setup_engine(t, find_design("divide"), w, kWidth, kHeight);
    size_t begin = 0;
    while (begin < quad.size()) {
      const auto major = [&](size_t i) { return setup.x_major ? quad[i].x : quad[i].y; };
      size_t end = begin;
      while (end < quad.size() && major(end) == major(begin)) ++end;
      const int64_t last = int64_t(end - begin) - 1;
      std::vector<int64_t> points = {0};
      int64_t at = 0;
      for (; last - at >= 16; at += 16) points.insert(points.end(), {at + 8, at + 16});
      for (int64_t bit = 8; bit >= 1; bit /= 2) {
        if (((last - at) & bit) == 0) continue;
        if (bit > 1) points.push_back(at + bit / 2);
        points.push_back(at += bit);
      }
      for (const int64_t p : points) {
        const size_t i = begin + size_t(p);
        // Both round the same exact value, from s_frac and from the reciprocal product.
        EXPECT_LE(std::abs(quad[i].u - exact[i].u), 1) << "triangle " << n << " pixel " << i;
        EXPECT_LE(std::abs(quad[i].v - exact[i].v), 1) << "triangle " << n << " pixel " << i;
        ++compared;
      }
      begin = end;
    }
  }
  EXPECT_GT(compared, 1000);
}

}  // namespace
}  // namespace cdsim

namespace cdsim {
namespace {

// cdsim::quotient (T, S, eps and divide's u, v): the numerator rounded to
// quotient_guard_bits beyond the format first, then its product with the
// reciprocal rounded again. Against x = numerator R 2^-(frac + rb + e), the
// value with the same reciprocal held exactly (a long double of 64 bits of
// mantissa for products of at most 60 bits): within half an ulp plus
// 2^-(guard + 1) of one, saturated (and flagged) only where x leaves the format,
// and equal to x rounded once when the numerator has no bit below the guard.
TEST(Quotient, IsTheProductWithTheReciprocalWithinHalfAnUlpAndTheGuard) {
  std::mt19937_64 rng(37);
  int64_t compared = 0, saturated_seen = 0, exact_operands = 0;
  for (int guard : {0, 2, 4, 8}) {
    for (int n = 0; n < 20000; ++n) {
      const fx::Format format{static_cast<int>(4 + rng() % 14), static_cast<int>(rng() % 16), true};
      const int recip_bits = static_cast<int>(8 + rng() % 17);
      const int numerator_frac = static_cast<int>(rng() % 9);
      const fx::Wide q = static_cast<fx::Wide>(1 + rng() % (uint64_t{1} << (1 + rng() % 40)));
      const Reciprocal r = reciprocal(q, recip_bits);
      // Numerators around q times the format's range, so that some saturate.
      const int numerator_bits = fx::bit_length(q) + format.int_bits + numerator_frac + static_cast<int>(rng() % 3);
      fx::Wide numerator = static_cast<fx::Wide>(rng() % (uint64_t{1} << std::min(numerator_bits, 62)));
      if (rng() % 2) numerator = -numerator;
      bool saturated = false;
      const fx::Wide got = quotient(numerator, numerator_frac, r, recip_bits, format, guard, &saturated);
      const long double x = std::ldexp(static_cast<long double>(numerator) * static_cast<long double>(r.mantissa),
                                       -(numerator_frac + recip_bits + r.exponent));
      const long double ulp = std::ldexp(1.0L, -format.frac_bits);
      const long double got_value = std::ldexp(static_cast<long double>(got), -format.frac_bits);
      const long double hi = static_cast<long double>(format.max_raw()) * ulp;
      const long double lo = static_cast<long double>(format.min_raw()) * ulp;
      // The numerator's rounding moves x by at most half its last place times
      // R 2^-rb <= 1: 2^-(guard + 1) ulp.
      const long double slack = ulp * (0.5L + std::ldexp(1.0L, -guard - 1) + 0x1p-40L);
      ++compared;
      if (saturated) {
        ++saturated_seen;
        ASSERT_TRUE(got == format.max_raw() || got == format.min_raw());
        ASSERT_TRUE(x > hi - slack || x < lo + slack) << "x " << static_cast<double>(x);
        continue;
      }
      ASSERT_LE(std::fabs(got_value - x), slack)
          << "guard " << guard << ", numerator " << static_cast<double>(numerator) << ", q " << static_cast<double>(q);
      const int dropped = numerator_frac + r.exponent - format.frac_bits - guard;
      if (dropped <= 0 || numerator % (fx::Wide{1} << dropped) == 0) {
        ++exact_operands;
        bool once_saturated = false;
        ASSERT_EQ(got, fx::narrow(numerator * r.mantissa, numerator_frac + recip_bits + r.exponent, format,
                                  fx::Round::Nearest, fx::Overflow::Saturate, &once_saturated));
      }
    }
  }
  EXPECT_GT(saturated_seen, 1000);
  EXPECT_GT(exact_operands, 1000);
  EXPECT_EQ(compared, 80000);
}

}  // namespace
}  // namespace cdsim
