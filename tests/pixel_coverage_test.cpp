// Pixel coverage (model/pixel_coverage.cpp): the column walker's spans against a brute-force pixel test, the
// top-left rule on exact pixel centres and edges, and watertightness of a
// closed mesh.
#include <gtest/gtest.h>

#include <set>

#include "column_walker.hpp"
#include "test_support.hpp"

namespace cdsim {
namespace {

using testing::brute_force_pixels;

UnitTriangle snapped(std::array<std::array<double, 2>, 3> xy, const Widths& w) {
  ScreenTriangle s;
  for (size_t i = 0; i < 3; ++i) s.vertex[i] = {xy[i][0], xy[i][1], 1.0, 0.0, 0.0};
  return to_unit(s, w, 0);
}

std::set<std::pair<int64_t, int64_t>> fragment_set(const std::vector<Fragment>& fragments) {
  std::set<std::pair<int64_t, int64_t>> out;
  for (const auto& f : fragments) out.emplace(f.x, f.y);
  return out;
}

// The walker accumulates each edge's span end from column to column (as the
// RTL does, without a divider); covered_span divides for every column. They
// must agree on every column, for long slivers and vertices far outside the
// viewport too, where a span end moves thousands of pixels per column.
TEST(Coverage, AccumulatedSpanEndsEqualDivisionOnEveryColumn) {
  std::mt19937_64 rng(77);
  int64_t columns = 0;
  for (const Widths& w : {Widths{}, testing::wide_widths()}) {
    for (int n = 0; n < 400; ++n) {
      ScreenTriangle s = testing::random_triangle(rng, 8192, 8192);
      if (n % 4 == 1) {  // a sliver: the third vertex a fraction of a pixel off an edge
        s.vertex[2].x = s.vertex[0].x + 0.3 + 1e-3 * (s.vertex[1].x - s.vertex[0].x);
        s.vertex[2].y = s.vertex[0].y + 1e-3 * (s.vertex[1].y - s.vertex[0].y);
      }
      if (n % 4 == 2)  // far outside the viewport
        for (auto& v : s.vertex) v.x = (v.x - 4096) * 6.5, v.y = (v.y - 4096) * 6.5;
      if (n % 4 == 3)  // on pixel centres: edges pass exactly through centres
        for (auto& v : s.vertex) v.x = std::floor(v.x / 64) * 64 + 0.5, v.y = std::floor(v.y / 64) * 64 + 0.5;
      const UnitTriangle t = to_unit(s, w, 0);
      for (const Design& d : {find_design("cd-linear"), find_design("cd-dense4")}) {
        const cdsim::Setup setup = setup_engine(t, d, w, 8192, 8192);
        if (setup.empty) continue;
        ColumnWalker walker(setup, w);
        const int64_t limit = std::min<int64_t>(setup.major_count, 3000);
        for (int64_t o = 0; o < limit; ++o, walker.advance(), ++columns) {
          const ColumnState a = walker.column(), b = walk_column(setup, o, w);
          ASSERT_EQ(a.span.lo, b.span.lo) << "triangle " << n << " column " << o;
          ASSERT_EQ(a.span.hi, b.span.hi) << "triangle " << n << " column " << o;
          ASSERT_EQ(a.line_shift, b.line_shift) << "triangle " << n << " column " << o;
          ASSERT_EQ(a.weight, b.weight) << "triangle " << n << " column " << o;
          ASSERT_EQ(a.direction, b.direction) << "triangle " << n << " column " << o;
        }
      }
    }
  }
  EXPECT_GT(columns, 100000);
}

TEST(Coverage, SpansMatchBruteForceForRandomTriangles) {
  std::mt19937_64 rng(1234);
  const Widths w;
  for (int n = 0; n < 300; ++n) {
    const UnitTriangle t = to_unit(testing::random_triangle(rng, 48, 40), w, 0);
    const auto expected = brute_force_pixels(t, w, 48, 40);
    for (const Design& d : all_designs()) {
      const auto fragments = testing::run_unit(d, w, 48, 40, t);
      ASSERT_EQ(fragments.size(), expected.size()) << d.name << " triangle " << n;
      const auto got = fragment_set(fragments);
      ASSERT_EQ(got.size(), fragments.size()) << d.name << ": a pixel was emitted twice";
      const std::set<std::pair<int64_t, int64_t>> want(expected.begin(), expected.end());
      ASSERT_EQ(got, want) << d.name << " triangle " << n;
    }
  }
}

TEST(Coverage, TopEdgeOnPixelCentresIsCoveredBottomEdgeIsNot) {
  const Widths w;
  // Pixel centres of row 2 lie at y = 2.5: the horizontal edge at y = 2.5 is a
  // top edge of the lower triangle and a bottom edge of the upper one.
  const UnitTriangle below = snapped({{{0.5, 2.5}, {8.5, 2.5}, {4.5, 6.5}}}, w);
  const UnitTriangle above = snapped({{{0.5, 2.5}, {4.5, -1.5}, {8.5, 2.5}}}, w);
  const EdgeSet eb = make_edges(below, w.subpixel_bits), ea = make_edges(above, w.subpixel_bits);
  for (int x = 1; x <= 7; ++x) {
    EXPECT_TRUE(covers(eb, x, 2)) << "top edge pixel " << x;
    EXPECT_FALSE(covers(ea, x, 2)) << "bottom edge pixel " << x;
  }
}

TEST(Coverage, LeftEdgeOnPixelCentresIsCoveredRightEdgeIsNot) {
  const Widths w;
  // Vertical edge at x = 3.5 (pixel centres of column 3).
  const UnitTriangle right_of = snapped({{{3.5, 0.5}, {3.5, 8.5}, {7.5, 4.5}}}, w);
  const UnitTriangle left_of = snapped({{{3.5, 0.5}, {-0.5, 4.5}, {3.5, 8.5}}}, w);
  const EdgeSet er = make_edges(right_of, w.subpixel_bits), el = make_edges(left_of, w.subpixel_bits);
  for (int y = 1; y <= 7; ++y) {
    EXPECT_TRUE(covers(er, 3, y)) << "left edge pixel " << y;
    EXPECT_FALSE(covers(el, 3, y)) << "right edge pixel " << y;
  }
}

TEST(Coverage, VertexOnPixelCentreBelongsToExactlyOneOfAFan) {
  const Widths w;
  // Eight triangles around the pixel centre (4.5, 4.5), both windings.
  const double c = 4.5;
  const std::array<std::array<double, 2>, 8> ring = {
      {{c + 3, c}, {c + 3, c + 3}, {c, c + 3}, {c - 3, c + 3}, {c - 3, c}, {c - 3, c - 3}, {c, c - 3}, {c + 3, c - 3}}};
  int hits = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    auto a = ring[i], b = ring[(i + 1) % ring.size()];
    if (i % 2) std::swap(a, b);
    hits += covers(make_edges(snapped({{{c, c}, a, b}}, w), w.subpixel_bits), 4, 4);
  }
  EXPECT_EQ(hits, 1);
}

TEST(Coverage, ClosedMeshCoversEveryPixelExactlyOnce) {
  // A jittered grid reaching past the viewport, cut into triangles with random
  // diagonals and windings; a third of the vertices sit exactly on pixel centres.
  const Widths w;
  const int width = 97, height = 71, cells = 9;
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> jitter(-3.0, 3.0);
  std::uniform_int_distribution<int> coin(0, 2);
  const double step_x = (width + 20.0) / cells, step_y = (height + 20.0) / cells;
  std::vector<std::vector<std::array<double, 2>>> grid(cells + 1, std::vector<std::array<double, 2>>(cells + 1));
  for (int i = 0; i <= cells; ++i)
    for (int j = 0; j <= cells; ++j) {
      double x = -10.0 + i * step_x, y = -10.0 + j * step_y;
      if (i > 0 && i < cells && j > 0 && j < cells) {
        x += jitter(rng), y += jitter(rng);
        if (coin(rng) == 0) x = std::floor(x) + 0.5, y = std::floor(y) + 0.5;
      }
      grid[size_t(i)][size_t(j)] = {x, y};
    }
  std::vector<int> count(size_t(width * height), 0);
  const Design& design = find_design("cd-linear");
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const auto p00 = grid[size_t(i)][size_t(j)], p10 = grid[size_t(i + 1)][size_t(j)];
      const auto p01 = grid[size_t(i)][size_t(j + 1)], p11 = grid[size_t(i + 1)][size_t(j + 1)];
      std::vector<std::array<std::array<double, 2>, 3>> tris;
      if (coin(rng) % 2) tris = {{{p00, p10, p11}}, {{p00, p11, p01}}};
      else tris = {{{p00, p10, p01}}, {{p10, p11, p01}}};
      for (auto tri : tris) {
        if (coin(rng) == 1) std::swap(tri[1], tri[2]);
        for (const auto& f : testing::run_unit(design, w, width, height, snapped(tri, w)))
          ++count[size_t(f.y * width + f.x)];
      }
    }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      ASSERT_EQ(count[size_t(y * width + x)], 1) << "pixel (" << x << ", " << y << ")";
}

}  // namespace
}  // namespace cdsim
