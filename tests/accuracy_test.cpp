// With wide widths each design computes its algorithm without visible
// arithmetic error: constant-depth designs agree with an ideal long-double
// version of the same algorithm, and `divide` with the exact reference.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace cdsim
