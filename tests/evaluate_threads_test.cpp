// evaluate() with its error measurement on several threads must give what one
// thread gives, bit for bit: every statistic (sums in the fragments' order),
// the worst pixel, and the visitor called in the same order.
#include <gtest/gtest.h>

#include <cstdint>

#include "evaluate.hpp"
#include "exact.hpp"
#include "scene.hpp"

namespace cdsim {
namespace {

struct Visited {
  int64_t count = 0;
  uint64_t hash = 1469598103934665603ull;  // FNV-1a over (triangle, x, y, exact u)
  void add(int64_t triangle, const Fragment& f, const ExactSample& x) {
    for (const int64_t word : {triangle, int64_t{f.x}, int64_t{f.y}, static_cast<int64_t>(x.u * 4096)}) {
      hash ^= static_cast<uint64_t>(word);
      hash *= 1099511628211ull;
    }
    ++count;
  }
};

void expect_same_stats(const ErrorStats& a, const ErrorStats& b) {
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_EQ(a.rms, b.rms);
  EXPECT_EQ(a.p99, b.p99);
  EXPECT_EQ(a.max, b.max);
  EXPECT_EQ(a.footprint_max, b.footprint_max);
  EXPECT_EQ(a.texel_mismatch, b.texel_mismatch);
  EXPECT_EQ(a.over_lsb, b.over_lsb);
}

TEST(EvaluateThreads, ThreeThreadsGiveOneThreadsResult) {
  const Widths w;
  // The default scene: 2.8 M fragments, so about eleven chunks of 2^18.
  const PreparedScene scene = prepare(default_scene(), w);
  for (const char* name : {"cd-linear", "divide"}) {
    SCOPED_TRACE(name);
    Visited one, three;
    const FragmentVisitor visit_one = [&](int64_t t, const Fragment& f, const ExactSample& x) { one.add(t, f, x); };
    const FragmentVisitor visit_three = [&](int64_t t, const Fragment& f, const ExactSample& x) {
      three.add(t, f, x);
    };
    const DesignResult a = evaluate(scene, find_design(name), w, true, &visit_one, 1);
    const DesignResult b = evaluate(scene, find_design(name), w, true, &visit_three, 3);
    ASSERT_GT(a.pixels, int64_t{1} << 20);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(a.cycles, b.cycles);
    EXPECT_EQ(a.flagged_pixels, b.flagged_pixels);
    EXPECT_GT(a.error.mean, 0.0);
    expect_same_stats(a.error, b.error);
    expect_same_stats(a.error_unflagged, b.error_unflagged);
    EXPECT_EQ(a.worst.triangle, b.worst.triangle);
    EXPECT_EQ(a.worst.fragment.x, b.worst.fragment.x);
    EXPECT_EQ(a.worst.fragment.y, b.worst.fragment.y);
    EXPECT_EQ(a.worst.error, b.worst.error);
    EXPECT_EQ(one.count, a.pixels);
    EXPECT_EQ(one.count, three.count);
    EXPECT_EQ(one.hash, three.hash);
  }
}

}  // namespace
}  // namespace cdsim
