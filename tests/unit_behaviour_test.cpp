// Behaviour of the unit on constructed triangles: screen-parallel triangles,
// both orientations, |g| = 1 and one LSB either side, table overflow, cycle
// counts worked by hand, and refusal of bad vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

#include "correction_adder.hpp"
#include "derived_widths.hpp"
#include "kim_datapath.hpp"
#include "test_support.hpp"

namespace cdsim {
namespace {

double max_error(const std::vector<Fragment>& fragments, const ExactReference& exact, int out_frac) {
  double worst = 0;
  for (const Fragment& f : fragments) {
    const ExactSample x = exact.at_pixel(f.x, f.y);
    const long double lsb = std::ldexp(1.0L, -out_frac);
    worst = std::max(worst, double(std::max(std::fabs(f.u * lsb - x.u), std::fabs(f.v * lsb - x.v))));
  }
  return worst;
}

TEST(UnitBehaviour, TriangleParallelToTheScreenIsExactInEveryDesign) {
  const Widths w;
  // Equal w; u, v on the 1/256 grid so the inputs are exact; 300 pixels wide.
  const ScreenTriangle s = testing::screen_triangle(
      {{{{3.2, 4.7, 7.0, 10.0, 20.0}}, {{310.4, 40.1, 7.0, 900.5, 61.25}}, {{50.3, 250.9, 7.0, -300.75, 812.0}}}});
  const UnitTriangle t = to_unit(s, w, 0);
  const ExactReference exact(s, t, w.subpixel_bits);
  for (const Design& d : all_designs()) {
    const auto fragments = testing::run_unit(d, w, 400, 300, t);
    ASSERT_GT(fragments.size(), 1000u);
    // Only the output rounding remains: half an LSB, plus T and S rounding far
    // below it; the Kim-style fraction is truncated to kim_frac bits first.
    const double bound = d.kind == Design::Kind::Kim
                             ? std::ldexp(1.0, -w.kim_frac) + std::ldexp(1.0, -w.out_frac - 1)
                             : std::ldexp(1.0, -w.out_frac);
    EXPECT_LE(max_error(fragments, exact, w.out_frac), bound) << d.name;
  }
  const ::cdsim::Setup setup = setup_engine(t, find_design("cd-none"), w, 400, 300);
  EXPECT_TRUE(setup.x_major);
  EXPECT_EQ(setup.g, 0);
}

// q = 1/w is a plane; build w at three snapped vertices from q = base + a x + b y.
ScreenTriangle with_depth_plane(std::array<std::array<double, 2>, 3> xy, double base, double a,
                                double b) {
  ScreenTriangle s;
  for (size_t i = 0; i < 3; ++i) {
    const double q = base + a * xy[i][0] + b * xy[i][1];
    s.vertex[i] = {xy[i][0], xy[i][1], 1.0 / q, 40.0 * xy[i][0] + 3.0 * xy[i][1], 7.0 * xy[i][1]};
  }
  return s;
}

TEST(UnitBehaviour, FloorLikeTrianglesAreXMajorAndWallLikeAreYMajor) {
  const Widths w = testing::wide_widths();
  const std::array<std::array<double, 2>, 3> xy = {{{10.0, 10.0}, {200.0, 30.0}, {60.0, 180.0}}};
  const ScreenTriangle floor = with_depth_plane(xy, 0.5, 0.0005, -0.002);  // q changes along y
  const ScreenTriangle wall = with_depth_plane(xy, 0.5, -0.002, 0.0005);   // q changes along x
  for (const auto& [s, x_major] : {std::pair{floor, true}, std::pair{wall, false}}) {
    const UnitTriangle t = to_unit(s, w, 0);
    for (const Design& d : all_designs()) {
      const ::cdsim::Setup setup = setup_engine(t, d, w, 256, 256);
      EXPECT_EQ(setup.x_major, x_major) << d.name;
      if (d.kind != Design::Kind::ConstantDepth) continue;
      const testing::IdealConstantDepth ideal(t, setup, w);
      const auto fragments = testing::run_unit(d, w, 256, 256, t);
      ASSERT_GT(fragments.size(), 5000u);
      for (const Fragment& f : fragments) {
        const auto i = ideal.at_pixel(f.x, f.y);
        ASSERT_NEAR(std::ldexp(double(f.u), -w.out_frac), double(i.u), 1e-3) << d.name;
      }
    }
  }
}

TEST(UnitBehaviour, SlopeOfOneAndOneLsbEitherSide) {
  // g = -q_x / q_y. With g_frac = 8, make q_x / q_y = -255/256, -1 and -257/256
  // exactly: vertex q values are then exact binary32 numbers.
  Widths w;
  w.g_frac = 8;
  const std::array<std::array<double, 2>, 3> xy = {{{4.0, 6.0}, {120.0, 20.0}, {30.0, 110.0}}};
  struct Case {
    double qx;
    bool x_major;
    int64_t g;
  } cases[] = {{255, true, -255}, {256, true, -256}, {257, false, -255}};
  for (const Case& c : cases) {
    // q = 1 + (qx x + 256 y) / 2^16 with x, y on the 1/256 grid: exact in binary32.
    const ScreenTriangle s = with_depth_plane(xy, 1.0, c.qx / 65536.0, 256.0 / 65536.0);
    const UnitTriangle t = to_unit(s, w, 0);
    const ExactReference exact(s, t, w.subpixel_bits);
    for (const Design& d : all_designs()) {
      const ::cdsim::Setup setup = setup_engine(t, d, w, 160, 160);
      EXPECT_EQ(setup.x_major, c.x_major) << d.name << " q_x " << c.qx;
      EXPECT_EQ(setup.g, c.g) << d.name << " q_x " << c.qx;
      const auto fragments = testing::run_unit(d, w, 160, 160, t);
      EXPECT_EQ(fragments.size(), testing::brute_force_pixels(t, w, 160, 160).size()) << d.name;
      // Lines are tilted 45 degrees, so a pixel is up to half a line from its own:
      // no design may do worse than half the footprint, and linear correction
      // must do far better.
      // Not perspective-correct by design; adaptive's bound is tested in adaptive_test.cpp.
      if (d.kind == Design::Kind::Affine || d.kind == Design::Kind::Adaptive) continue;
      const double bound = d.correction ? 0.05 : (d.kind == Design::Kind::ConstantDepth ? 60.0 : 0.01);
      EXPECT_LT(max_error(fragments, exact, w.out_frac), bound) << d.name << " q_x " << c.qx;
    }
  }
}

std::vector<std::tuple<int32_t, int32_t, int64_t, int64_t>> sorted(const std::vector<Fragment>& fragments) {
  std::vector<std::tuple<int32_t, int32_t, int64_t, int64_t>> out;
  for (const auto& f : fragments) out.emplace_back(f.x, f.y, f.u, f.v);
  std::sort(out.begin(), out.end());
  return out;
}

TEST(UnitBehaviour, TableOverflowGivesTheSamePixelsAndValuesAsADeepTable) {
  const ScreenTriangle s = testing::screen_triangle(
      {{{{2.3, 1.7, 1.0, 0.0, 0.0}}, {{190.2, 60.4, 6.0, 800.0, 100.0}}, {{40.6, 170.9, 2.5, 50.0, 700.0}}}});
  for (const char* name : {"cd-none", "cd-linear", "cd-dense2-linear", "cd-dense4"}) {
    Widths deep, shallow;
    deep.table_depth = 4096;
    shallow.table_depth = 8;
    const UnitTriangle t = to_unit(s, deep, 0);
    TriangleRecord deep_record, shallow_record;
    const auto a = testing::run_unit(find_design(name), deep, 256, 256, t, &deep_record);
    const auto b = testing::run_unit(find_design(name), shallow, 256, 256, t, &shallow_record);
    ASSERT_GT(a.size(), 5000u);
    EXPECT_EQ(sorted(a), sorted(b)) << name;
    EXPECT_EQ(deep_record.bands, 1) << name;
    EXPECT_GT(shallow_record.bands, 10) << name;
    EXPECT_TRUE(shallow_record.flags & flag::kBanded) << name;
    EXPECT_FALSE(deep_record.flags & flag::kBanded) << name;
    EXPECT_GT(shallow_record.cycles, deep_record.cycles) << name;
  }
}

TEST(UnitBehaviour, CyclesOfAHandWorkedTriangle) {
  // Right triangle (0,0) (8,0) (0,8) in pixels, constant w: box 8x8 pixels,
  // g = 0, x-major, 8 pixel lines (rows 0..7). Centres with i + j <= 6 are
  // covered (i + j = 7 lies on the hypotenuse, which is neither top nor left): 28.
  const Widths w;  // reciprocal latency 4
  // Setup: 4 stages, then the serial dividers: a span end has 43 quotient bits
  // at subpixel_bits 8, 4 bits per cycle (docs/rtl.md, "Setup engine").
  const int64_t kSetup = 4 + (43 + 3) / 4;
  ASSERT_EQ(kSetup, derive(w).setup_cycles);
  const ScreenTriangle s = testing::screen_triangle(
      {{{{0, 0, 2.0, 0, 0}}, {{8, 0, 2.0, 64, 0}}, {{0, 8, 2.0, 0, 64}}}});
  const UnitTriangle t = to_unit(s, w, 0);
  // The walk: one cycle per pixel, and a column cycle for column 0 (the first)
  // only: columns 1..6 are loaded in the last pixel cycle of the span before,
  // and in column 6's, the walker stands on column 7, the last, without a
  // pixel, so the pass ends (rtl/cd_scan_unit.sv, StPixel).
  const int64_t kColumnCycles = 1;
  const std::pair<const char*, int64_t> expected[] = {
      {"cd-none", kSetup + (8 + 4) + kColumnCycles + 28},
      {"cd-linear", kSetup + (10 + 4) + kColumnCycles + 28},
      {"cd-dense2", kSetup + (15 + 4) + kColumnCycles + 28},        // lines 0..14 at half-pixel spacing
      {"cd-dense2-linear", kSetup + (17 + 4) + kColumnCycles + 28},
      {"divide", kSetup + kColumnCycles + 28 + 4},
  };
  // The first triangle of a stream also holds the unit in its accept cycle and
  // its record cycle. At setup_fifo_depth 2 (the default) it moves into the
  // fill stage in its last setup cycle and the back takes it a cycle later: a
  // constant-depth triangle is filled meanwhile, a per-pixel design waits that
  // cycle and one more to load the walker from its context.
  ASSERT_EQ(w.setup_fifo_depth, 2);
  for (const auto& [name, cycles] : expected) {
    TriangleRecord r;
    const auto fragments = testing::run_unit(find_design(name), w, 64, 64, t, &r);
    EXPECT_EQ(fragments.size(), 28u) << name;
    const bool table = find_design(name).kind == Design::Kind::ConstantDepth;
    EXPECT_EQ(r.cycles, 1 + cycles + (table ? 0 : 2) + 1) << name;
    EXPECT_EQ(r.setup_cycles + r.fill_cycles + r.walk_cycles + r.record_cycles, r.cycles) << name;
    EXPECT_EQ(r.setup_cycles, 1 + kSetup + 1) << name;
    EXPECT_EQ(r.record_cycles, 1) << name;
  }
  // At depth 1 the back takes it from the setup engine: a per-pixel design
  // only spends the load cycle.
  Widths overlapped = w;
  overlapped.setup_fifo_depth = 1;
  for (const auto& [name, cycles] : expected) {
    TriangleRecord r;
    testing::run_unit(find_design(name), overlapped, 64, 64, t, &r);
    const bool table = find_design(name).kind == Design::Kind::ConstantDepth;
    EXPECT_EQ(r.cycles, 1 + cycles + (table ? 0 : 1) + 1) << name;
    EXPECT_EQ(r.setup_cycles, 1 + kSetup) << name;
  }
  // Run one after another (setup_fifo_depth 0) there is no load cycle.
  Widths serial = w;
  serial.setup_fifo_depth = 0;
  for (const auto& [name, cycles] : expected) {
    TriangleRecord r;
    testing::run_unit(find_design(name), serial, 64, 64, t, &r);
    EXPECT_EQ(r.cycles, 1 + cycles + 1) << name;
  }
}

TEST(UnitBehaviour, ZeroAreaAndEmptyBoxCostOnlySetup) {
  const Widths w;
  const ScreenTriangle line = testing::screen_triangle(
      {{{{1, 1, 1, 0, 0}}, {{9, 5, 1, 0, 0}}, {{17, 9, 1, 0, 0}}}});
  const ScreenTriangle between_centres = testing::screen_triangle(
      {{{{1.6, 1.6, 1, 0, 0}}, {{1.9, 1.6, 1, 0, 0}}, {{1.6, 1.9, 1, 0, 0}}}});
  for (const auto& s : {line, between_centres}) {
    TriangleRecord r;
    EXPECT_TRUE(testing::run_unit(find_design("cd-linear"), w, 32, 32, to_unit(s, w, 0), &r).empty());
    // Accept, setup, the cycle in the fill stage (setup_fifo_depth 2) and record.
    ASSERT_EQ(w.setup_fifo_depth, 2);
    EXPECT_EQ(r.cycles, 1 + derive(w).setup_cycles + 1 + 1);
    EXPECT_EQ(r.fill_cycles + r.walk_cycles, 0);
  }
}

TEST(UnitBehaviour, BadVerticesAreRefusedNamingTheTriangle) {
  const Widths w;
  const double nan = std::nan(""), inf = HUGE_VAL;
  const std::pair<ScreenVertex, const char*> bad[] = {
      {{nan, 1, 1, 0, 0}, "non-finite"},
      {{1, inf, 1, 0, 0}, "non-finite"},
      {{1, 1, 0.0, 0, 0}, "w = 0"},
      {{1, 1, -2.0, 0, 0}, "w = -2"},
      {{40000, 1, 1, 0, 0}, "outside"},
      {{1, 1, 1, 0, 33000}, "texture coordinates"},
  };
  for (const auto& [vertex, words] : bad) {
    ScreenTriangle s = testing::screen_triangle({{{{0, 0, 1, 0, 0}}, {{5, 0, 1, 0, 0}}, {{0, 5, 1, 0, 0}}}});
    s.vertex[2] = vertex;
    try {
      to_unit(s, w, 17);
      ADD_FAILURE() << "accepted a vertex that should be refused: " << words;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("triangle 17"), std::string::npos) << message;
      EXPECT_NE(message.find("vertex 2"), std::string::npos) << message;
      EXPECT_NE(message.find(words), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace cdsim

namespace cdsim {
namespace {

TEST(UnitBehaviour, KimAndAffineCyclesOfAHandWorkedTriangle) {
  // The right triangle of CyclesOfAHandWorkedTriangle, u = 8x and v = 8y texels:
  // columns 0..6 hold 7, 6, ..., 1 covered pixels and column 7 none; down a
  // column I_u is constant and I_v moves 8 texels per pixel.
  Widths w;  // out_int 16 (span division), kim_frac 8, recip_latency 4
  // The first triangle of a stream at setup_fifo_depth 2: accept, setup, its
  // cycle in the fill stage, the walker's load cycle, the walk, and the record.
  ASSERT_EQ(w.setup_fifo_depth, 2);
  const int64_t kAroundWalk = 1 + (4 + (43 + 3) / 4) + 2 + 1;  // as in CyclesOfAHandWorkedTriangle
  const ScreenTriangle s = testing::screen_triangle(
      {{{{0, 0, 2.0, 0, 0}}, {{8, 0, 2.0, 64, 0}}, {{0, 8, 2.0, 0, 64}}}});
  const UnitTriangle t = to_unit(s, w, 0);
  const int64_t columns = 8, spans = 7, pixels = 28, span_division = 16;
  // Kim, by hand (docs/designs.md): a span's column cycle, its division
  // (out_int cycles), then its first pixel is handed to the fraction stage in
  // the next cycle; each later pixel n cycles after the one before, n = max(1,
  // steps) here = 8, and at least kim_frac for kim-iter. The fraction stage
  // offers a fragment kim_frac cycles after its hand-off. The empty column 7
  // takes the cycle after column 6's only hand-off, so the unit then waits
  // kim_frac - 1 more cycles for the last fragment.
  int64_t spans_8 = 0;  // each span: column, division, first pixel, 8 per later pixel
  for (int64_t n = 1; n <= 7; ++n) spans_8 += 1 + span_division + 1 + 8 * (n - 1);
  const int64_t kim_pipe = kAroundWalk + spans_8 + 1 + (8 - 1);
  // kim-iter: 8 fraction cycles never hold the integer stage back here (the
  // later pixels take 8 cycles anyway, the first one of a span 18 after the
  // span before's last), so it takes the same cycles.
  const int64_t kim_iter = kim_pipe;
  const std::pair<const char*, int64_t> expected[] = {
      {"kim-iter", kim_iter}, {"kim-pipe", kim_pipe},
      // Plain affine loads a span in the last pixel cycle of the one before: a
      // column cycle for column 0 only. The subdivided designs and Kim take a
      // column cycle for every column (their span start needs it).
      {"affine", kAroundWalk + 1 + pixels},
      {"affine-sub8", kAroundWalk + columns + pixels + spans * 4},  // one segment per span: no stall
      {"affine-sub16", kAroundWalk + columns + pixels + spans * 4},
  };
  for (const auto& [name, cycles] : expected) {
    TriangleRecord r;
    const auto fragments = testing::run_unit(find_design(name), w, 64, 64, t, &r);
    EXPECT_EQ(fragments.size(), 28u) << name;
    EXPECT_EQ(r.cycles, cycles) << name;
  }
  // Unrolling four unit steps per cycle: each later pixel of a span takes 2 cycles.
  {
    Widths u = w;
    u.kim_unroll = 4;
    int64_t unrolled = 0;
    for (int64_t n = 1; n <= 7; ++n) unrolled += 1 + span_division + 1 + 2 * (n - 1);
    TriangleRecord r;
    testing::run_unit(find_design("kim-pipe"), u, 64, 64, t, &r);
    EXPECT_EQ(r.cycles, kAroundWalk + unrolled + 1 + (8 - 1));
  }
  // A slow iterative fraction stage (kim_frac 16) and a short division
  // (out_int 8, |u|, |v| <= 64 still fit): kim-iter hands off a pixel every 16
  // cycles from the first one on (cycle 1 + 8 of the walk), span starts
  // included, since a span start's 1 + 8 + 1 cycles are fewer. The last of
  // the 28 fragments comes 16 cycles after the last hand-off.
  {
    Widths slow = w;
    slow.kim_frac = 16;
    slow.out_int = 8;
    const UnitTriangle ts = to_unit(s, slow, 0);
    TriangleRecord r;
    testing::run_unit(find_design("kim-iter"), slow, 64, 64, ts, &r);
    EXPECT_EQ(r.cycles, kAroundWalk + (1 + 8) + 16 * (pixels - 1) + 16 + 1);
    // kim-pipe at the same widths: 1 + 8 + 1 + 8 (n - 1) per span, column 7,
    // then 16 - 1 cycles for the last fragment.
    int64_t pipe = 0;
    for (int64_t n = 1; n <= 7; ++n) pipe += 1 + 8 + 1 + 8 * (n - 1);
    testing::run_unit(find_design("kim-pipe"), slow, 64, 64, ts, &r);
    EXPECT_EQ(r.cycles, kAroundWalk + pipe + 1 + (16 - 1));
  }
}

TEST(UnitBehaviour, KimPixelWithDepthOutHoldsTheIntegerPart) {
  // q = 2 - minor along the span (q <= 0 from minor 2 on), U = 20.5 q and
  // V = -3.25 q texels, 8 fraction bits: u = 20.5, v = -3.25 where q > 0.
  const Widths w;
  cdsim::Setup s;
  s.q.at_ref = 2;
  s.q.per_minor = -1;
  s.u.at_ref = 2 * 5248;  // 20.5 * 2^8 = 5248
  s.u.per_minor = -5248;
  s.v.at_ref = 2 * -832;  // -3.25 * 2^8 = -832
  s.v.per_minor = 832;
  uint32_t flags = 0;
  const KimPixel first = kim_pixel(s, 0, 0, w, nullptr, &flags);
  EXPECT_EQ(flags, 0u);
  EXPECT_EQ(first.integer_u, 20);
  EXPECT_EQ(first.integer_v, -4);  // floor(-3.25)
  EXPECT_EQ(first.value.u, 20 * 256 + 128);
  EXPECT_EQ(first.value.v, -3 * 256 - 64);
  // q = 0: depth_range, output 0, and the iteration keeps I (no steps).
  const KimPixel held = kim_pixel(s, 0, 2, w, &first, &flags);
  EXPECT_EQ(flags, flag::kDepthRange);
  EXPECT_TRUE(held.depth_out);
  EXPECT_EQ(held.integer_u, 20);
  EXPECT_EQ(held.integer_v, -4);
  EXPECT_EQ(held.value.u, 0);
  EXPECT_EQ(held.value.v, 0);
  EXPECT_FALSE(held.value.saturated);
  // At a span's first pixel the span division sets I = 0.
  const KimPixel start = kim_pixel(s, 0, 3, w, nullptr, &flags);
  EXPECT_TRUE(start.depth_out);
  EXPECT_EQ(start.integer_u, 0);
  EXPECT_EQ(start.integer_v, 0);
}

TEST(UnitBehaviour, KimPixelSaturatesOutsideTheIntegerRegister) {
  // u = 40000 texels > 2^15 - 1: I clamps to the out_int register's max and
  // the output saturates with a flag; v = -40000 to the min.
  const Widths w;
  cdsim::Setup s;
  s.q.at_ref = 1;
  s.u.at_ref = int64_t{40000} << w.uv_in_frac;
  s.v.at_ref = -(int64_t{40000} << w.uv_in_frac);
  uint32_t flags = 0;
  const KimPixel p = kim_pixel(s, 0, 0, w, nullptr, &flags);
  EXPECT_EQ(p.integer_u, (1 << 15) - 1);
  EXPECT_EQ(p.integer_v, -(1 << 15));
  EXPECT_TRUE(p.value.saturated);
  EXPECT_EQ(p.value.u, (int64_t{1} << 23) - 1);
  EXPECT_EQ(p.value.v, -(int64_t{1} << 23));
}

TEST(UnitBehaviour, AffineSubdivisionStallsWhenSegmentsAreShorterThanTheDivider) {
  // One column 40 pixels tall, constant w: with recip_latency 12 and segments of
  // 8, each segment after the first stalls 12 - 8 = 4 cycles.
  Widths w;
  w.recip_latency = 12;
  // Accept, setup, the fill stage's cycle and the walker's load cycle
  // (setup_fifo_depth 2) and the record of the first triangle of a stream, as
  // in CyclesOfAHandWorkedTriangle.
  ASSERT_EQ(w.setup_fifo_depth, 2);
  const int64_t kAroundWalk = 1 + (4 + (43 + 3) / 4) + 2 + 1;
  const ScreenTriangle s = testing::screen_triangle(
      {{{{0.2, 0.0, 1.0, 0, 0}}, {{0.8, 0.0, 1.0, 0, 0}}, {{0.5, 40.0, 1.0, 0, 40}}}});
  TriangleRecord r;
  const auto fragments = testing::run_unit(find_design("affine-sub8"), w, 8, 64, to_unit(s, w, 0), &r);
  const int64_t pixels = static_cast<int64_t>(fragments.size());
  ASSERT_GT(pixels, 30);
  // Segments cover pixel steps 0..pixels-1 eight at a time (the last may be
  // short). Each later segment's end point is issued when the segment before
  // starts, 8 cycles before it is needed, whatever the later segment's own
  // length: every segment after the first waits 12 - 8 cycles.
  const int64_t segments = (pixels - 1 + 7) / 8;
  ASSERT_GE(segments, 3);
  const int64_t stalls = (segments - 1) * (12 - 8);
  EXPECT_EQ(r.cycles, kAroundWalk + 1 + pixels + 12 + stalls);
}

// The cycles a triangle keeps the unit busy when it runs alone, after setup:
// fill and walk, as the phases give them.
int64_t busy_after_setup(const TrianglePhases& p) {
  int64_t cycles = p.scan + p.walk;
  for (const TrianglePhases::Band& band : p.bands) cycles += band.fill + band.walk;
  return cycles;
}

TEST(UnitSchedule, ASourceThatWaitsForEachRecordLosesTheOverlap) {
  // Two per-pixel triangles of 20 walk cycles at setup_fifo_depth 1, S = 15.
  // Offered back to back: the first is accepted in cycle 0, taken in 15, loads
  // the walker in 16, walks 17..36 and records in 37; the second, accepted in
  // 15 (the take), is set up by 30 and taken in 37, records in 37 + 22 = 59.
  // Offered only from the first record's cycle on: accepted in 37, taken in
  // 52, recorded in 74.
  Widths w;
  w.setup_fifo_depth = 1;
  ASSERT_EQ(derive(w).setup_cycles, 15);
  TrianglePhases walk;
  walk.kind = TrianglePhases::Kind::Walk;
  walk.walk = 20;
  UnitSchedule back_to_back(w), after_record(w);
  after_record.offer_after_record(true);
  EXPECT_EQ(back_to_back.next(walk).total(), 38);
  EXPECT_EQ(back_to_back.next(walk).total(), 59 - 37);
  EXPECT_EQ(after_record.next(walk).total(), 38);
  EXPECT_EQ(after_record.next(walk).total(), 74 - 37);
  EXPECT_EQ(after_record.last().accept, 37);
}

TEST(UnitBehaviour, TimingLayerTurnsWorkIntoPhasesAndComputeSkipsIt) {
  // The timing layer alone, on work written by hand: two bands of 7 and 5
  // lines over 4 columns holding 3 + 0 + 2 + 1 and 1 + 1 + 0 + 0 pixels.
  Widths w;
  w.recip_latency = 3;
  w.setup_fifo_depth = 1;  // the back takes a triangle from the setup engine
  w.table_banks = 1;
  const int64_t kSetup = derive(w).setup_cycles;
  TriangleWork work;
  work.walked = true;
  work.columns = 4;
  work.band_lines = {7, 5};
  work.column_pixels = {3, 0, 2, 1, 1, 1, 0, 0};
  work.read_tops = {1, 2, 3, 5, 6, 4, 2, 4};  // each pixel's highest table address
  const TrianglePhases cd = UnitTiming(find_design("cd-linear"), w).phases(work);
  EXPECT_EQ(cd.kind, TrianglePhases::Kind::Bands);
  ASSERT_EQ(cd.bands.size(), 2u);
  EXPECT_EQ(cd.bands[0].fill, 7 + 3);
  // Pass 1: a column cycle loads column 0; in the first two of its three pixel
  // cycles the walker passes over column 1 (empty), so columns 2 and 3 are
  // loaded in the last pixel cycles before them: 1 column cycle. Pass 2:
  // column 0's cycle, column 1 loaded in column 0's pixel cycle; column 1's
  // single pixel cycle leaves no cycle to pass over column 2, so columns 2
  // and 3 take a column cycle each: 3.
  EXPECT_EQ(cd.bands[0].walk, 1 + 6);
  EXPECT_EQ(cd.bands[1].fill, 5 + 3);
  EXPECT_EQ(cd.bands[1].walk, 3 + 2);
  // Each pixel's read goes the cycle before its pixel cycle. Pass 1 reads
  // addresses 1, 2, 3, 5, 6, 4 in pass cycles 0..5: a read of A in cycle c
  // needs the walk to start 3 + 1 + A - c cycles after the first fill cycle,
  // at most 3 + 1 + 5 - 3 = 6 (address 5 in cycle 3); the walk's end needs
  // fill - walk + 1 = 4. Pass 2 reads 2 and 4 in cycles 0 and 1: 3 + 1 + 4 - 1 = 7.
  EXPECT_EQ(cd.bands[0].read_lag, 6);
  EXPECT_EQ(cd.bands[1].read_lag, 7);
  // A box with no possible pixel line: one pass over the columns.
  TriangleWork no_line = work;
  no_line.band_lines.clear();
  no_line.column_pixels = {0, 0, 0, 0};
  const TrianglePhases scan = UnitTiming(find_design("cd-none"), w).phases(no_line);
  EXPECT_EQ(scan.kind, TrianglePhases::Kind::Scan);
  EXPECT_EQ(scan.scan, 4);
  // divide: one pass, drained once.
  work.band_lines.clear();
  work.column_pixels = {3, 0, 2, 1};
  const TrianglePhases divide = UnitTiming(find_design("divide"), w).phases(work);
  EXPECT_EQ(divide.kind, TrianglePhases::Kind::Walk);
  EXPECT_EQ(divide.walk, 1 + 6 + 3);
  // affine-sub8 with a 12-cycle divider: spans of 1, 9, 10 and 17 pixels have
  // 1, 1, 2 and 2 segments; each waits 12 cycles, each later segment 4 more.
  w.recip_latency = 12;
  work.column_pixels = {1, 9, 10, 17};
  EXPECT_EQ(UnitTiming(find_design("affine-sub8"), w).phases(work).walk, 4 + 37 + 4 * 12 + 2 * 4);
  // quad-sub16 with a 4-cycle divider, counted by hand from each column cycle
  // (0, which issues the first point): a 1-pixel span takes its pixel when the
  // point arrives (4). A 2-pixel span issues its end in 1 and takes its pixels
  // in 5, 6. A 4-pixel span is segments of 2 and 1: points at 1, 2 (arriving
  // 6), pixels in 6, 7; the second segment's end is issued when the first takes
  // its first pixel (6), so its pixels come in 10, 11. A 17-pixel span is one
  // 16-pixel segment: middle and end issued in 1, 2, pixels in 6 .. 22.
  w.recip_latency = 4;
  work.column_pixels = {1, 2, 4, 17};
  EXPECT_EQ(UnitTiming(find_design("quad-sub16"), w).phases(work).walk, 4 + 4 + 6 + 11 + 22);
  // A triangle that ends after setup.
  EXPECT_EQ(UnitTiming(find_design("kim-pipe"), w).phases(TriangleWork{}).kind, TrianglePhases::Kind::Empty);

  // ScanUnit::compute gives run's values without cycles and leaves the
  // schedule alone: the run after it is the stream's first triangle (accept,
  // setup, a per-pixel design's load cycle, fill and walk, record).
  const ScreenTriangle s = testing::screen_triangle(
      {{{{3.2, 4.7, 2.0, 10.0, 20.0}}, {{60.4, 10.1, 7.0, 90.5, 61.25}}, {{20.3, 50.9, 4.0, -30.75, 81.0}}}});
  const UnitTriangle t = to_unit(s, w, 0);
  for (const Design& d : all_designs()) {
    if (d.kind == Design::Kind::Adaptive) continue;  // a split engine and a unit: adaptive_test.cpp
    ScanUnit unit(d, w, 64, 64);
    std::vector<Fragment> computed, ran;
    const TriangleRecord c = unit.compute(t, &computed);
    const TrianglePhases phases = unit.phases();
    const TriangleRecord r = unit.run(t, &ran);
    ASSERT_EQ(computed.size(), ran.size()) << d.name;
    EXPECT_EQ(c.cycles, 0) << d.name;
    const int64_t load = phases.kind == TrianglePhases::Kind::Walk ? 1 : 0;
    EXPECT_EQ(r.cycles, 1 + kSetup + load + busy_after_setup(phases) + 1) << d.name;
    EXPECT_EQ(c.pixels, r.pixels) << d.name;
    EXPECT_EQ(c.flags, r.flags) << d.name;
    int64_t pixels = 0;
    for (const int32_t n : unit.work().column_pixels) pixels += n;
    EXPECT_EQ(pixels, r.pixels) << d.name;
    // A constant-depth band's reads stay in its lines, so early_walk's wait
    // is at most the whole fill, and its end is never before the fill's.
    if (phases.kind == TrianglePhases::Kind::Bands) {
      EXPECT_EQ(static_cast<int64_t>(unit.work().read_tops.size()), r.pixels) << d.name;
      for (const TrianglePhases::Band& b : phases.bands) {
        EXPECT_GE(b.read_lag, b.fill - b.walk + 1) << d.name;
        EXPECT_LE(b.read_lag, b.fill) << d.name;
      }
    }
  }
}

// Hand-written phases for the schedule tests.
TrianglePhases empty_phases() { return TrianglePhases{}; }
TrianglePhases scan_phases(int64_t columns) {
  TrianglePhases p;
  p.kind = TrianglePhases::Kind::Scan;
  p.scan = columns;
  return p;
}
TrianglePhases walk_phases(int64_t walk) {
  TrianglePhases p;
  p.kind = TrianglePhases::Kind::Walk;
  p.walk = walk;
  return p;
}
TrianglePhases band_phases(std::vector<TrianglePhases::Band> bands) {
  TrianglePhases p;
  p.kind = TrianglePhases::Kind::Bands;
  p.bands = std::move(bands);
  return p;
}

// Default widths: setup_cycles = 4 stages + 11 divider cycles (43 quotient
// bits, 4 a cycle), as in CyclesOfAHandWorkedTriangle.
Widths schedule_widths(int fifo_depth, int banks = 1) {
  Widths w;
  w.setup_fifo_depth = fifo_depth;
  w.table_banks = banks;
  return w;
}
constexpr int64_t kScheduleSetup = 15;

TEST(UnitSchedule, OneAfterAnotherEachTriangleCostsSetupFillWalkAcceptAndRecord) {
  const Widths w = schedule_widths(0);
  ASSERT_EQ(derive(w).setup_cycles, kScheduleSetup);
  UnitSchedule schedule(w);
  // Without overlap each triangle holds the unit for its accept cycle, setup,
  // fill and walk, and its record cycle, and the next is accepted after it.
  struct Step {
    TrianglePhases phases;
    int64_t busy;    // fill + walk, by hand
    int64_t record;  // its record cycle, by hand
  };
  const Step steps[] = {
      {empty_phases(), 0, 0 + 15 + 1},                               // accepted in 0
      {scan_phases(5), 5, 17 + 15 + 5 + 1},                          // accepted in 17
      {walk_phases(20), 20, 39 + 15 + 20 + 1},                       // accepted in 39
      {band_phases({{10, 12}, {8, 6}}), 36, 76 + 15 + 36 + 1},       // accepted in 76
      {walk_phases(3), 3, 129 + 15 + 3 + 1},                         // accepted in 129
  };
  int64_t sum = 0;
  for (const Step& step : steps) {
    const TriangleCycles c = schedule.next(step.phases);
    EXPECT_EQ(c.total(), kScheduleSetup + step.busy + 2);
    EXPECT_EQ(c.setup, 1 + kScheduleSetup);
    EXPECT_EQ(c.fill + c.walk, step.busy);
    EXPECT_EQ(c.record, 1);
    EXPECT_EQ(schedule.last().record, step.record);
    sum += c.total();
  }
  // The scene's clocks: from the first accept (cycle 0) to the last record.
  EXPECT_EQ(sum, 148 + 1);
}

TEST(UnitSchedule, OverlappedRunOfPerPixelTrianglesTakesTheSlowerOfSetupAndWalk) {
  // Identical per-pixel triangles at setup_fifo_depth 1: the front end sets up
  // the next while the back end walks, so in steady state a triangle takes
  // max(setup_cycles, load + walk + record) = max(15, W + 2) cycles.
  const Widths w = schedule_widths(1);
  ASSERT_EQ(derive(w).setup_cycles, kScheduleSetup);
  struct Case {
    int64_t walk;
    std::vector<int64_t> records;  // record cycles of 4 triangles, by hand
    int64_t period;
  };
  const Case cases[] = {
      // Walk-bound: accepted 0, 15, 37, 59; taken 15, 37, 59, 81.
      {20, {37, 59, 81, 103}, 22},
      // Setup-bound: accepted 0, 15, 30, 45; taken when set up, 15, 30, 45, 60.
      {5, {22, 37, 52, 67}, 15},
      // Balanced: W + 2 = 15, the back end takes each in its record cycle.
      {13, {30, 45, 60, 75}, 15},
  };
  for (const Case& k : cases) {
    UnitSchedule schedule(w);
    int64_t sum = 0;
    for (size_t i = 0; i < k.records.size(); ++i) {
      const TriangleCycles c = schedule.next(walk_phases(k.walk));
      EXPECT_EQ(schedule.last().record, k.records[i]) << "W " << k.walk << " triangle " << i;
      EXPECT_EQ(c.walk, k.walk + 1) << "W " << k.walk;  // the load cycle, then the walk
      EXPECT_EQ(c.record, 1);
      // The first: accept, setup, load, walk, record. Then the period.
      EXPECT_EQ(c.total(), i == 0 ? 1 + 15 + 1 + k.walk + 1 : k.period) << "W " << k.walk << " triangle " << i;
      sum += c.total();
    }
    EXPECT_EQ(sum, k.records.back() + 1) << "W " << k.walk;
  }
  // Walk-bound: the back end never waits for setup after the first triangle.
  UnitSchedule walk_bound(w);
  walk_bound.next(walk_phases(20));
  EXPECT_EQ(walk_bound.next(walk_phases(20)).setup, 0);
  // Setup-bound: it waits 15 - (5 + 2) = 8 cycles a triangle.
  UnitSchedule setup_bound(w);
  EXPECT_EQ(setup_bound.next(walk_phases(5)).setup, 1 + 15);
  EXPECT_EQ(setup_bound.next(walk_phases(5)).setup, 8);
}

TEST(UnitSchedule, OverlappedBandsHoldTheFrontEndUntilTheirLastFill) {
  // Two bands (fill 10, walk 12; fill 8, walk 6) at setup_fifo_depth 1. The
  // front end fills the bands, so it accepts the next triangle only in the
  // cycle the last band's fill ends.
  const Widths w = schedule_widths(1);
  ASSERT_EQ(derive(w).setup_cycles, kScheduleSetup);
  UnitSchedule schedule(w);
  const TrianglePhases two_bands = band_phases({{10, 12}, {8, 6}});
  // Triangle 0: accepted 0, set up by 15, taken 15; band 0 fills 16..25 and
  // walks 26..37, band 1 fills 38..45 and walks 46..51; record 52.
  TriangleCycles c = schedule.next(two_bands);
  EXPECT_EQ(schedule.last().accept, 0);
  EXPECT_EQ(schedule.last().taken, 15);
  EXPECT_EQ(schedule.last().record, 52);
  EXPECT_EQ(c.total(), 53);
  EXPECT_EQ(c.setup, 16);
  EXPECT_EQ(c.fill, 18);
  EXPECT_EQ(c.walk, 18);
  EXPECT_EQ(c.record, 1);
  // Triangle 1, per-pixel walk 4: accepted 45, set up by 60, taken 60 (the
  // back end has been free since 52), loads in 61, walks 62..65, record 66.
  c = schedule.next(walk_phases(4));
  EXPECT_EQ(schedule.last().accept, 45);
  EXPECT_EQ(schedule.last().taken, 60);
  EXPECT_EQ(schedule.last().record, 66);
  EXPECT_EQ(c.total(), 66 - 52);
  EXPECT_EQ(c.setup, 60 - 52);
  EXPECT_EQ(c.walk, 1 + 4);
  // Triangle 2, the two bands again: accepted 60, taken 75; fills 76..85,
  // walks 86..97, fills 98..105, walks 106..111; record 112.
  c = schedule.next(two_bands);
  EXPECT_EQ(schedule.last().accept, 60);
  EXPECT_EQ(schedule.last().record, 112);
  EXPECT_EQ(c.total(), 112 - 66);
  EXPECT_EQ(c.setup, 75 - 66);
  // Triangle 3, empty: accepted 105 (triangle 2's last fill), taken 120, record 121.
  c = schedule.next(empty_phases());
  EXPECT_EQ(schedule.last().accept, 105);
  EXPECT_EQ(schedule.last().record, 121);
  EXPECT_EQ(c.total(), 121 - 112);
  EXPECT_EQ(c.setup, 120 - 112);
}

TEST(UnitSchedule, TheFillStageAndASecondBankFillTheNextTriangleDuringThisWalk) {
  // Triangles of one band (fill 10, walk 20), S = 15. By hand:
  // - depth 2, two banks: triangle 0 is accepted in 0, set up by 15, moves into
  //   the fill stage in 15 and is filled 16..25 (bank 0) while the back takes
  //   it in 16; the back waits 17..25, loads the band in 26 and walks 26..45,
  //   record 46. Triangle 1, accepted in 15, moves in at 30 (the stage has
  //   been free since its fill ended in 25) and is filled 31..40 into bank 1;
  //   the back takes it in 46 (the record cycle), waits in 47 (the band's load
  //   cycle), walks 48..67, record 68. Triangle 2 goes into bank 0 again, free
  //   since 45: record 90. The walk bounds it: 22 cycles a triangle.
  // - depth 2, one bank: triangle 1's fill waits for triangle 0's walk to end
  //   (45): it fills 46..55 and walks 56..75, record 76; triangle 2 moves in at
  //   55, fills 76..85, record 106: fill and walk in turn, 30 a triangle.
  // - depth 1, one bank (the fill reads the setup engine): triangle 1 is
  //   accepted only as triangle 0's fill ends (25), taken in 46, filled 47..56,
  //   record 77; triangle 2 accepted in 56, taken in 77, record 108.
  struct Case {
    int depth, banks;
    std::vector<int64_t> records;
  };
  const Case cases[] = {{2, 2, {46, 68, 90}}, {2, 1, {46, 76, 106}}, {1, 1, {46, 77, 108}}};
  const TrianglePhases band = band_phases({{10, 20}});
  for (const Case& k : cases) {
    UnitSchedule schedule(schedule_widths(k.depth, k.banks));
    ASSERT_EQ(derive(schedule_widths(k.depth, k.banks)).setup_cycles, kScheduleSetup);
    int64_t previous = -1;
    for (size_t i = 0; i < k.records.size(); ++i) {
      const TriangleCycles c = schedule.next(band);
      EXPECT_EQ(schedule.last().record, k.records[i]) << "depth " << k.depth << " banks " << k.banks << " triangle " << i;
      EXPECT_EQ(c.total(), i == 0 ? k.records[0] + 1 : k.records[i] - previous) << "depth " << k.depth;
      EXPECT_EQ(c.walk, 20);
      previous = schedule.last().record;
    }
  }
  // Two banks within one triangle (depth 1): band 1 (fill 8) is filled into
  // bank 1 during band 0's walk. Taken in 15; band 0 fills 16..25 and walks
  // 26..37; band 1 fills 26..33, is loaded in 38 and walks 39..44; record 45.
  UnitSchedule two_banks(schedule_widths(1, 2));
  const TriangleCycles c = two_banks.next(band_phases({{10, 12}, {8, 6}}));
  EXPECT_EQ(two_banks.last().record, 45);
  EXPECT_EQ(c.setup, 16);
  EXPECT_EQ(c.fill, 10 + 1);
  EXPECT_EQ(c.walk, 12 + 6);
  // The setup engine is free for the next triangle when band 1's fill ends (33).
  two_banks.next(empty_phases());
  EXPECT_EQ(two_banks.last().accept, 33);
}

TEST(UnitSchedule, AnEarlyWalkStartsWithItsFillAndStallsUntilEachLineIsWritten) {
  // One band (fill 10, walk 12) whose reads need the walk to start 7 cycles
  // after the band's first fill cycle, S = 15, one bank. By hand, at depth 0:
  // accepted in 0, taken in 15, filled 16..25. Without early_walk the walk
  // starts after the fill: 26..37, record 38. With it the back leaves its
  // wait in 16 and walks from 17, stalls 16 + 7 - 17 = 6 cycles for its lines
  // and ends in 17 + 6 + 12 - 1 = 34: record 35.
  Widths w = schedule_widths(0);
  ASSERT_EQ(derive(w).setup_cycles, kScheduleSetup);
  const TrianglePhases one = band_phases({{10, 12, 7}});
  UnitSchedule late(w);
  EXPECT_EQ(late.next(one).fill, 10);
  EXPECT_EQ(late.last().record, 38);
  w.early_walk = 1;
  UnitSchedule early(w);
  const TriangleCycles c = early.next(one);
  EXPECT_EQ(early.last().record, 35);
  EXPECT_EQ(c.fill, 1 + 6);  // the cycle that starts the walk, and the stalls
  EXPECT_EQ(c.walk, 12);
  EXPECT_EQ(c.total(), 35 + 1);
  // Two bands in one bank (depth 1): band 1 (fill 8, walk 6, lag 3) is filled
  // only once band 0's walk has ended in 34: filled 35..42, walked from 36
  // after 35 + 3 - 36 = 2 stalls, ending in 36 + 2 + 6 - 1 = 43 (after its
  // last fill cycle): record 44.
  w.setup_fifo_depth = 1;
  UnitSchedule two(w);
  const TriangleCycles t = two.next(band_phases({{10, 12, 7}, {8, 6, 3}}));
  EXPECT_EQ(two.last().record, 44);
  EXPECT_EQ(t.fill, 7 + 1 + 2);
  EXPECT_EQ(t.walk, 12 + 6);
}

TEST(UnitSchedule, TheFirstTriangleCountsFromItsAcceptAndResetStartsAgain) {
  for (const int depth : {0, 1}) {
    UnitSchedule schedule(schedule_widths(depth));
    // Accept (cycle 0), setup 1..15, [load], walk, record.
    const int64_t first = 1 + 15 + depth + 9 + 1;
    EXPECT_EQ(schedule.next(walk_phases(9)).total(), first) << depth;
    EXPECT_EQ(schedule.last().accept, 0) << depth;
    EXPECT_EQ(schedule.last().record, first - 1) << depth;
    schedule.next(scan_phases(3));
    schedule.reset();
    EXPECT_EQ(schedule.next(walk_phases(9)).total(), first) << depth;
    EXPECT_EQ(schedule.last().accept, 0) << depth;
    // An empty triangle first: accept, setup, record.
    schedule.reset();
    EXPECT_EQ(schedule.next(empty_phases()).total(), 1 + 15 + 1) << depth;
  }
}

TEST(UnitSchedule, ClocksOfAStreamAddUpFromFirstAcceptToLastRecord) {
  // Random streams of every kind: the triangles' clocks add up to the cycles
  // from the first accept to the last record, both included. Overlapped, no
  // triangle after the first costs more than it would run one after another
  // (the first may cost its load cycle more).
  std::mt19937_64 rng(12);
  std::uniform_int_distribution<int> kind(0, 3), length(0, 40), bands(1, 3);
  for (int stream = 0; stream < 50; ++stream) {
    std::vector<TrianglePhases> phases;
    for (int i = 0; i < 30; ++i) {
      switch (kind(rng)) {
        case 0: phases.push_back(empty_phases()); break;
        case 1: phases.push_back(scan_phases(1 + length(rng))); break;
        case 2: phases.push_back(walk_phases(1 + length(rng))); break;
        default: {
          std::vector<TrianglePhases::Band> b;
          for (int n = bands(rng); n > 0; --n) {
            const int64_t fill = 5 + length(rng), walk = 1 + length(rng);
            // read_lag as a real band's: from fill - walk + 1 up to fill.
            const int64_t lag_lo = std::max<int64_t>(0, fill - walk + 1);
            b.push_back({fill, walk, std::uniform_int_distribution<int64_t>(lag_lo, fill)(rng)});
          }
          phases.push_back(band_phases(b));
        }
      }
    }
    for (const auto& [depth, banks] : {std::pair{0, 1}, {1, 1}, {1, 2}, {2, 1}, {2, 2}}) {
      UnitSchedule schedule(schedule_widths(depth, banks));
      // The same stream with early_walk: never a record later, the same walk.
      Widths early_widths = schedule_widths(depth, banks);
      early_widths.early_walk = 1;
      UnitSchedule early(early_widths);
      int64_t sum = 0, early_sum = 0;
      for (size_t i = 0; i < phases.size(); ++i) {
        const TrianglePhases& p = phases[i];
        const TriangleCycles c = schedule.next(p);
        const int64_t serial = kScheduleSetup + busy_after_setup(p) + 2;
        EXPECT_GE(c.setup, 0);
        EXPECT_EQ(c.record, 1);
        if (depth == 0) {
          EXPECT_EQ(c.total(), serial) << "stream " << stream << " triangle " << i;
        } else {
          // The first may cost the cycle it spends in the fill stage, and a
          // per-pixel design its load cycle.
          const int64_t first = (depth > 1 ? 1 : 0) + (p.kind == TrianglePhases::Kind::Walk ? 1 : 0);
          EXPECT_LE(c.total(), serial + (i == 0 ? first : 0))
              << "stream " << stream << " triangle " << i << " depth " << depth << " banks " << banks;
        }
        sum += c.total();
        const TriangleCycles e = early.next(p);
        EXPECT_EQ(e.walk, c.walk);
        EXPECT_LE(early.last().record, schedule.last().record)
            << "stream " << stream << " triangle " << i << " depth " << depth << " banks " << banks;
        early_sum += e.total();
      }
      EXPECT_EQ(sum, schedule.last().record + 1) << "stream " << stream << " depth " << depth << " banks " << banks;
      EXPECT_EQ(early_sum, early.last().record + 1) << "stream " << stream << " depth " << depth;
    }
  }
}

}  // namespace
}  // namespace cdsim

// The walker's accumulator is 64-bit where the widths allow it and 128-bit
// beyond (s_int=30 with 20 fraction bits needs 66 bits): both give the same
// fragment wherever 64 bits suffice, and the 128-bit one is exact beyond.
TEST(UnitBehaviour, WideWalkerAccumulatorEqualsTheNarrowOneAndIsExactBeyond) {
  cdsim::Widths w;
  ASSERT_TRUE(cdsim::walker_fits_64(w));
  std::mt19937_64 rng(7);
  const auto draw = [&](int bits) {
    return static_cast<int64_t>(rng() % (uint64_t{1} << bits)) - (int64_t{1} << (bits - 1));
  };
  for (int i = 0; i < 2000; ++i) {
    cdsim::TableEntry own, neighbour;
    own.t_u = draw(w.t_int + w.t_frac), own.t_v = draw(w.t_int + w.t_frac);
    own.s_u = draw(w.s_int + w.s_frac - 6), own.s_v = draw(w.s_int + w.s_frac - 6);
    neighbour = own;
    neighbour.t_u += draw(20), neighbour.s_v += draw(12);
    const int64_t offset = draw(14), weight = static_cast<int64_t>(rng() % (uint64_t{1} << w.d_frac));
    const auto narrow = cdsim::correction_adder_in<int64_t>(own, &neighbour, offset, weight, 1, false, w);
    const auto wide = cdsim::correction_adder_in<cdsim::fx::Wide>(own, &neighbour, offset, weight, 1, false, w);
    EXPECT_EQ(narrow.value.u, wide.value.u);
    EXPECT_EQ(narrow.value.v, wide.value.v);
    EXPECT_EQ(narrow.flags, wide.flags);
  }
  // Past 64 bits: two neighbour lines at the ends of S's range (s_int=30),
  // 16383 columns out, 2^63 apart; half way between them is about 0, which
  // the 128-bit accumulator gives and 64 bits (their difference wraps) do not.
  w.s_int = 30;
  ASSERT_FALSE(cdsim::walker_fits_64(w));
  cdsim::TableEntry a, b;
  a.s_u = (int64_t{1} << 49) - 1;
  b.s_u = -(int64_t{1} << 49);
  const auto f = cdsim::correction_adder(a, &b, 16383, int64_t{1} << (w.d_frac - 1), 1, false, w);
  EXPECT_FALSE(f.value.saturated);
  EXPECT_LE(std::abs(f.value.u), 2);  // -16383 / 2 at 20 fraction bits, to 8
}
