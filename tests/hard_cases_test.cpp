// The hard-case suite (SPEC §9): each named case, run through every design at
// default widths, shows the behaviour written beside it in scene/hard_cases.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "adaptive_split.hpp"
#include "derived_widths.hpp"
#include "evaluate.hpp"
#include "hard_cases.hpp"
#include "line_geometry.hpp"
#include "column_walker.hpp"
#include "test_support.hpp"

namespace cdsim {
namespace {

// What one design did on one case.
struct CaseOutcome {
  int64_t pixels = 0, cycles = 0, bands = 0;
  double max_error = 0, max_footprint = 0, mean_error = 0;
  double max_unflagged_error = 0;
  uint32_t flags = 0;
  bool coverage_exact = true;
  std::string coverage_message;
  std::vector<TriangleRecord> records;
  std::vector<std::vector<Fragment>> fragments;  // kept only when asked
};

using Pixels = std::vector<std::pair<int32_t, int32_t>>;

// Brute force over each triangle's box: the covered pixels, sorted.
std::vector<Pixels> brute_force(const PreparedScene& scene, const Widths& w) {
  std::vector<Pixels> out;
  for (const UnitTriangle& t : scene.unit) {
    const EdgeSet edges = make_edges(t, w.subpixel_bits);
    const PixelBox box = bounding_box(t, w.subpixel_bits, scene.scene.width, scene.scene.height);
    Pixels pixels;
    for (int64_t y = box.y_lo; y <= box.y_hi; ++y)
      for (int64_t x = box.x_lo; x <= box.x_hi; ++x)
        if (covers(edges, x, y)) pixels.emplace_back(int32_t(x), int32_t(y));
    std::sort(pixels.begin(), pixels.end());
    out.push_back(std::move(pixels));
  }
  return out;
}

CaseOutcome run_case(const PreparedScene& scene, const std::vector<Pixels>& expected, const Design& d,
                     const Widths& w, bool keep_fragments = false) {
  CaseOutcome o;
  ScanUnit unit(d, w, scene.scene.width, scene.scene.height);
  double sum = 0;
  for (size_t i = 0; i < scene.unit.size(); ++i) {
    std::vector<Fragment> fragments;
    const TriangleRecord r = unit.run(scene.unit[i], &fragments);
    o.records.push_back(r);
    o.cycles += r.cycles;
    o.bands += r.bands;
    o.flags |= r.flags;
    Pixels got;
    for (const Fragment& f : fragments) got.emplace_back(f.x, f.y);
    std::sort(got.begin(), got.end());
    if (got != expected[i] && o.coverage_exact) {
      o.coverage_exact = false;
      o.coverage_message = fmt::format("triangle {} ({}): {} fragments, {} covered pixels", i,
                                       scene.scene.triangles[i].origin, got.size(), expected[i].size());
    }
    const ExactReference exact(scene.scene.triangles[i], scene.unit[i], w.subpixel_bits);
    for (const Fragment& f : fragments) {
      const PixelError e = pixel_error(f, exact.at_pixel(f.x, f.y), w.out_frac);
      o.max_error = std::max(o.max_error, e.texels);
      o.max_footprint = std::max(o.max_footprint, e.footprint);
      if (f.flags == 0) o.max_unflagged_error = std::max(o.max_unflagged_error, e.texels);
      sum += e.texels;
      ++o.pixels;
    }
    if (keep_fragments) o.fragments.push_back(std::move(fragments));
  }
  o.mean_error = o.pixels ? sum / double(o.pixels) : 0;
  return o;
}

class HardCase : public ::testing::Test {
 protected:
  // Runs every design on the case; checks what holds for every case: the exact
  // pixels are drawn, by every design.
  std::map<std::string, CaseOutcome> run_all(const std::string& name, const Widths& w = Widths{},
                                             bool keep_fragments = false) {
    scene_ = prepare(hard_case_scene("hard:" + name), w);
    const auto expected = brute_force(scene_, w);
    std::map<std::string, CaseOutcome> out;
    for (const Design& d : all_designs()) {
      out[d.name] = run_case(scene_, expected, d, w, keep_fragments);
      EXPECT_TRUE(out[d.name].coverage_exact) << name << " " << d.name << ": " << out[d.name].coverage_message;
    }
    return out;
  }
  PreparedScene scene_;
};

bool is_constant_depth(const std::string& name) { return find_design(name).kind == Design::Kind::ConstantDepth; }

TEST_F(HardCase, Parallel) {
  const Widths w;
  const double lsb = std::ldexp(1.0, -w.out_frac);
  for (const auto& [name, o] : run_all("parallel")) {
    const double bound = find_design(name).kind == Design::Kind::Kim ? std::ldexp(1.0, -w.kim_frac) + lsb / 2 : lsb;
    EXPECT_LE(o.max_error, bound) << name;
    EXPECT_EQ(o.flags, 0u) << name;
  }
}

TEST_F(HardCase, SlopeOne) {
  const Widths w;
  const auto outcomes = run_all("slope-one");
  // Built as q_x/q_y = -(1 - 2^-16), -1, -(1 + 2^-16), then mirrored along y.
  const std::pair<bool, int64_t> expected[] = {{true, -65535}, {true, -65536}, {false, -65535},
                                               {true, 65535},  {true, 65536},  {false, 65535}};
  for (size_t i = 0; i < scene_.unit.size(); ++i) {
    const ::cdsim::Setup s = setup_engine(scene_.unit[i], find_design("cd-linear"), w, scene_.scene.width, scene_.scene.height);
    EXPECT_EQ(s.x_major, expected[i].first) << "triangle " << i;
    EXPECT_EQ(s.g, expected[i].second) << "triangle " << i;
  }
  EXPECT_LT(outcomes.at("cd-linear").max_footprint, 0.05);
  EXPECT_LT(outcomes.at("divide").max_footprint, 0.01);
}

// A floor strip reaching a few pixels from its horizon, the horizon across the
// pixel grid (issue 41). Its expectation: every design within 1e-2
// footprints, or its triangles handled by a documented fallback. Linear
// correction between lines a gap apart errs by about 1/(4 d) footprints d
// gaps from the horizon, so cd-linear cannot hold it (the case needs the
// fallback); cd-linear-div and cd-persp-div send both triangles to divide's
// datapath, cd-persp's perspective weight holds on its own. cd-none errs by
// up to half a line gap anywhere (EdgeOn); adaptive stops at its depth limit
// (docs/designs.md, docs/robustness.md).
TEST_F(HardCase, Grazing) {
  const auto o = run_all("grazing");
  EXPECT_GT(o.at("cd-linear").max_footprint, 1e-2) << "the case should need the fallback";
  for (const char* name : {"divide", "cd-persp", "cd-linear-div", "cd-persp-div"}) {
    EXPECT_LT(o.at(name).max_footprint, 1e-2) << name;
    EXPECT_EQ(o.at(name).flags & flag::kDatapath, 0u) << name;
  }
  for (const auto& [name, outcome] : o) EXPECT_GT(outcome.pixels, 50000) << name;
  // Far/near depth ratio over 1000, and lines of constant depth across the
  // pixel grid: neither axis-aligned (g != 0) in either triangle; the
  // fallback takes both.
  const Widths w;
  for (size_t i = 0; i < scene_.unit.size(); ++i) {
    const auto& v = scene_.scene.triangles[i].vertex;
    const auto [near, far] = std::minmax({v[0].w, v[1].w, v[2].w});
    EXPECT_GT(far / near, 1000.0) << "triangle " << i;
    const ::cdsim::Setup s =
        setup_engine(scene_.unit[i], find_design("cd-linear"), w, scene_.scene.width, scene_.scene.height);
    EXPECT_NE(s.g, 0) << "triangle " << i;
    EXPECT_FALSE(s.fallback) << "triangle " << i << ": cd-linear has no fallback";
    EXPECT_TRUE(setup_engine(scene_.unit[i], find_design("cd-linear-div"), w, scene_.scene.width,
                             scene_.scene.height)
                    .fallback)
        << "triangle " << i;
  }
}

// Small near-edge-on triangles whose far vertex lies within a few line gaps
// of the horizon of their plane: the triangles of the OpenArena maps that
// flagged (issue 41). The line phase keeps every line a pixel uses on the near
// side; without it, correction neighbours past the horizon are dropped and flagged.
TEST_F(HardCase, Horizon) {
  const uint32_t past = flag::kDepthRange | flag::kNeighbourDropped;
  {
    Widths w;
    w.line_phase_bits = 0;
    const auto o = run_all("horizon", w);
    EXPECT_NE(o.at("cd-linear").flags & flag::kNeighbourDropped, 0u) << "the case should need the phase";
    EXPECT_NE(o.at("cd-persp").flags & flag::kNeighbourDropped, 0u) << "the case should need the phase";
  }
  const Widths w;
  const auto o = run_all("horizon", w);
  for (const auto& [name, outcome] : o) {
    EXPECT_GT(outcome.pixels, 100) << name;
    if (is_constant_depth(name)) {
      EXPECT_EQ(outcome.flags & past, 0u) << name;
    }
  }
  EXPECT_LT(o.at("divide").max_footprint, 1e-2);
  // The far vertex of every triangle within 2 line gaps of its horizon.
  for (size_t i = 0; i < scene_.unit.size(); ++i) {
    const ::cdsim::Setup s = setup_engine(scene_.unit[i], find_design("cd-linear"), w, scene_.scene.width,
                                          scene_.scene.height);
    if (s.empty) continue;  // no pixel centre inside (the thinnest ones)
    EXPECT_LT(line_geometry(scene_.scene.triangles[i], scene_.unit[i], s, w).horizon_gaps, 2.0) << "triangle " << i;
  }
  // At the widest widths `cdsim choose` tries, cd-persp is as good as divide and flags nothing.
  Widths widest = w;
  for (const auto& [field, value] : std::vector<std::pair<int Widths::*, int>>{
           {&Widths::q_bits, 32}, {&Widths::plane_bits, 48}, {&Widths::recip_bits, 32}, {&Widths::g_frac, 30},
           {&Widths::t_int, 20}, {&Widths::t_frac, 24}, {&Widths::s_int, 20}, {&Widths::s_frac, 24},
           {&Widths::d_frac, 24}, {&Widths::eps_int, 16}, {&Widths::eps_frac, 30}, {&Widths::persp_frac, 30},
           {&Widths::persp_table_log2, 8}})
    widest.*field = value;
  const auto wide = run_all("horizon", widest);
  EXPECT_EQ(wide.at("cd-persp").flags & flag::kDatapath, 0u);
  EXPECT_LT(wide.at("cd-persp").max_footprint, std::ldexp(1.0, -8));
}

TEST_F(HardCase, EdgeOn) {
  const auto o = run_all("edge-on");
  EXPECT_LT(o.at("divide").max_footprint, 1e-2);
  // Off its line by up to half a pixel where the footprint itself changes fast:
  // cd-none stays within one footprint, and correction helps.
  EXPECT_LT(o.at("cd-none").max_footprint, 1.0);
  EXPECT_LT(o.at("cd-linear").mean_error, o.at("cd-none").mean_error);
  EXPECT_LT(o.at("cd-linear").max_footprint, o.at("cd-none").max_footprint);
  for (const auto& [name, outcome] : o) EXPECT_GT(outcome.pixels, 100000) << name;
}

TEST_F(HardCase, NearPlane) {
  const Scene scene = hard_case_scene("hard:near-plane");
  // Both triangles reach the unit, each with a vertex on the near plane: one
  // built there, the other cut there by homogeneous clipping.
  ASSERT_EQ(scene.triangles.size(), 2u);
  for (const auto& t : scene.triangles) {
    int on_plane = 0;
    for (const auto& v : t.vertex) {
      EXPECT_GE(v.w, 0.05 * (1 - 1e-12));
      on_plane += std::fabs(v.w - 0.05) < 1e-12;
    }
    EXPECT_GE(on_plane, 1) << t.origin;
  }
  const auto o = run_all("near-plane");
  const double lsb = std::ldexp(1.0, -Widths{}.out_frac);
  EXPECT_GT(o.at("divide").pixels, 1000);
  EXPECT_LT(o.at("divide").max_error, 2 * lsb + 2e-3);
}

TEST_F(HardCase, Sliver) {
  const Widths w;
  const auto o = run_all("sliver");
  for (const auto& [name, outcome] : o) {
    EXPECT_GT(outcome.pixels, 500) << name;
    // The walker spends at least a cycle on each column of each triangle's box.
    int64_t columns = 0;
    for (size_t i = 0; i < scene_.unit.size(); ++i) {
      const ::cdsim::Setup s = setup_engine(scene_.unit[i], find_design(name), w, scene_.scene.width, scene_.scene.height);
      columns += s.major_count;
    }
    EXPECT_GE(outcome.cycles, columns) << name;
  }
}

TEST_F(HardCase, Subpixel) {
  // One triangle after another, so that each one's clocks are its own.
  Widths w;
  w.setup_fifo_depth = 0;
  const auto o = run_all("subpixel", w);
  const size_t n = scene_.unit.size();
  for (const auto& [name, outcome] : o) {
    // The last three are zero-area: no pixels; accept, setup and record only.
    for (size_t i = n - 3; i < n; ++i) {
      EXPECT_EQ(outcome.records[i].pixels, 0) << name << " triangle " << i;
      // adaptive: the affine unit behind its split engine sets up at the leaves' widths.
      const Widths unit_widths = name == "adaptive" ? adaptive_leaf_widths(w) : w;
      EXPECT_EQ(outcome.records[i].cycles, 1 + derive(unit_widths).setup_cycles + 1) << name << " triangle " << i;
    }
    for (size_t i = 0; i < n; ++i) EXPECT_LE(outcome.records[i].pixels, 2) << name << " triangle " << i;
  }
}

TEST_F(HardCase, Watertight) {
  const auto o = run_all("watertight", Widths{}, true);
  for (const auto& [name, outcome] : o) {
    std::map<std::pair<int32_t, int32_t>, int> count;
    for (const auto& fragments : outcome.fragments)
      for (const Fragment& f : fragments) ++count[{f.x, f.y}];
    // Pixels 1..128 in x and y have centres inside the grid (0.5 .. 128.5).
    for (int32_t y = 1; y <= 127; ++y)
      for (int32_t x = 1; x <= 127; ++x) ASSERT_EQ((count[{x, y}]), 1) << name << " pixel " << x << ", " << y;
  }
}

TEST_F(HardCase, Viewport8k) {
  const auto o = run_all("viewport-8k");
  for (const auto& [name, outcome] : o) {
    EXPECT_GT(outcome.pixels, 500000) << name;
    if (is_constant_depth(name)) {
      EXPECT_TRUE(outcome.flags & flag::kBanded) << name;
    }
  }
  EXPECT_LT(o.at("divide").max_footprint, 1e-2);
}

TEST_F(HardCase, TexcoordRange) {
  const auto o = run_all("texcoord-range");
  for (const char* name : {"divide", "kim-iter", "kim-pipe"}) {
    EXPECT_EQ(o.at(name).flags & flag::kOutputSaturated, 0u) << name;
    EXPECT_LT(o.at(name).max_error, 0.02) << name;
  }
  // Wherever a saturation happens it is flagged: unflagged pixels of the
  // constant-depth designs stay within their off-line error of the footprint.
  for (const auto& [name, outcome] : o)
    if (is_constant_depth(name)) {
      EXPECT_LT(outcome.max_footprint, 0.6) << name;
    }
}

TEST_F(HardCase, TableOverflow) {
  // One table bank: a band's refill then waits for the walk of the band
  // before, so banding costs cycles. (With two, the next band is filled during
  // this band's walk, and a banded triangle may finish sooner than one whose
  // single band must be filled before its walk starts.)
  Widths one_bank;
  one_bank.table_banks = 1;
  Widths deep = one_bank;
  deep.table_depth = 4096;
  const auto shallow = run_all("table-overflow", one_bank, true);
  const auto expected = brute_force(scene_, deep);
  for (const Design& d : all_designs()) {
    if (d.kind != Design::Kind::ConstantDepth) continue;
    const CaseOutcome& banded = shallow.at(d.name);
    EXPECT_TRUE(banded.flags & flag::kBanded) << d.name;
    const CaseOutcome reference = run_case(scene_, expected, d, deep, true);
    EXPECT_FALSE(reference.flags & flag::kBanded) << d.name;
    EXPECT_GT(banded.cycles, reference.cycles) << d.name;
    for (size_t i = 0; i < scene_.unit.size(); ++i) {
      auto a = banded.fragments[i], b = reference.fragments[i];
      const auto order = [](const Fragment& l, const Fragment& r) { return std::tie(l.x, l.y) < std::tie(r.x, r.y); };
      std::sort(a.begin(), a.end(), order);
      std::sort(b.begin(), b.end(), order);
      ASSERT_EQ(a.size(), b.size()) << d.name;
      for (size_t k = 0; k < a.size(); ++k)
        ASSERT_TRUE(a[k].u == b[k].u && a[k].v == b[k].v) << d.name << " pixel " << a[k].x << ", " << a[k].y;
    }
  }
}

TEST_F(HardCase, HalfTie) {
  const Widths w;
  const auto o = run_all("half-tie");
  const ::cdsim::Setup s = setup_engine(scene_.unit[0], find_design("cd-linear"), w, scene_.scene.width, scene_.scene.height);
  ASSERT_TRUE(s.x_major);
  EXPECT_EQ(s.g, -(int64_t{1} << (w.g_frac - 1)));  // g = -1/2
  // In odd columns g o is on .5: rounded toward +inf, the pixel sits +1/2 from its line.
  const ColumnState odd = walk_column(s, 1, w);
  EXPECT_EQ(odd.line_shift, 0);
  EXPECT_EQ(odd.direction, 1);
  EXPECT_EQ(odd.weight, int64_t{1} << (w.d_frac - 1));
  EXPECT_LT(o.at("cd-linear").max_footprint, 0.05);
}

TEST_F(HardCase, BadInputIsRefusedBeforeTheUnit) {
  const Scene scene = hard_case_scene("hard:bad-input");
  for (size_t i = 0; i < scene.triangles.size(); ++i) {
    Scene one = scene;
    one.triangles = {scene.triangles[i]};
    try {
      prepare(one, Widths{});
      ADD_FAILURE() << "triangle " << i << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("hard:bad-input #"), std::string::npos) << e.what();
    }
  }
}

TEST(HardCases, AllCombinesEveryCaseButBadInput) {
  const Scene all = hard_case_scene("hard:all");
  size_t expected = 0;
  for (const auto& c : hard_cases())
    if (c.name != "bad-input") expected += hard_case_scene("hard:" + c.name).triangles.size();
  EXPECT_EQ(all.triangles.size(), expected);
  EXPECT_EQ(all.width, 8192);
  EXPECT_THROW(hard_case_scene("hard:no-such-case"), InputError);
}

}  // namespace
}  // namespace cdsim
