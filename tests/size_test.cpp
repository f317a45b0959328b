// Sizing (app/size.cpp) against independent evaluations of the model.
#include <gtest/gtest.h>

#include <algorithm>

#include "choose.hpp"
#include "design.hpp"
#include "evaluate.hpp"
#include "scene.hpp"
#include "size.hpp"
#include "sweep_file.hpp"
#include "widths.hpp"

namespace cdsim {
namespace {

// A loose footprint target lets narrow integer widths through wherever the
// footprint is large, even where they clamp. Sizing must not take a width
// that makes the datapath saturate on more triangles than the widest widths
// do (at 0.5 footprints cd-linear took t_int 14 and s_int 10: 58 triangles
// table_saturated, a 1.9e4-texel error, before it checked).
TEST(Size, NarrowingNeverAddsSaturatedTriangles) {
  const Widths defaults;
  const PreparedScene scene = prepare(default_scene(), defaults);
  const Design& design = find_design("cd-linear");
  const ErrorTarget target{0.5, "footprint", "max"};
  const Sizing sizing = size_design(design, {&scene}, defaults, target);
  ASSERT_TRUE(sizing.reachable);

  Widths wide = sizing.widths;  // every width cd-linear's accuracy depends on, at its widest
  wide.q_bits = 32;
  wide.plane_bits = 48;
  wide.g_frac = 30;
  wide.recip_bits = 32;
  wide.t_int = 20;
  wide.t_frac = 24;
  wide.s_int = 20;
  wide.s_frac = 24;
  wide.d_frac = 24;
  wide.table_depth = 16384;
  validate(wide);
  const DesignResult at_widest = evaluate(scene, design, wide);
  const DesignResult at_sized = evaluate(scene, design, sizing.widths);

  EXPECT_LE(at_sized.error.footprint_max, target.max_error);
  EXPECT_LT(sizing.widths.t_int + sizing.widths.s_int, wide.t_int + wide.s_int) << "nothing was narrowed";
  for (int f = 0; f < flag::kCount; ++f) {
    if ((1u << f) == flag::kBanded) continue;  // the table depth's business
    EXPECT_LE(at_sized.flagged_triangles[f], at_widest.flagged_triangles[f]) << flag::name(f);
  }
}

// choose's table halving: the depth it keeps meets the target, raises no new
// saturation flag and keeps the cycles within the budget, each measured here
// by a run of its own; and one more halving would break one of the three.
TEST(Size, ShrinkTableStopsAtTheLastDepthWithinBudget) {
  // A small scene (sized in a second), where cd-dense2's table halves once.
  const Widths defaults;
  const PreparedScene scene = prepare(load_scene(CDSIM_TEST_DATA "/small_scene.tri"), defaults);
  const Design& design = find_design("cd-dense2");
  const ErrorTarget target{0.5, "footprint", "max"};
  const double max_slowdown = 1.1;
  const Sizing sized = size_design(design, {&scene}, defaults, target);
  ASSERT_TRUE(sized.reachable);
  Sizing shrunk = sized;
  shrink_table(design, {&scene}, target, max_slowdown, sized.results.at(0).cycles, shrunk);

  const int depth = shrunk.widths.table_depth;
  bool halved = false;  // depth = the sized depth halved (rounding down) k >= 0 times
  for (int d = sized.widths.table_depth; d >= 4 && !halved; d /= 2) halved = d == depth;
  EXPECT_TRUE(halved) << depth << " lines from " << sized.widths.table_depth;
  EXPECT_LT(depth, sized.widths.table_depth) << "the scene no longer makes the table halve: pick another";
  Widths others = shrunk.widths;
  others.table_depth = sized.widths.table_depth;
  EXPECT_EQ(describe(others), describe(sized.widths)) << "only the table depth changes";

  const DesignResult at_sized = evaluate(scene, design, sized.widths);
  const auto within = [&](const DesignResult& r) {
    bool flags_ok = true;
    for (int f = 0; f < flag::kCount; ++f)
      if ((1u << f) != flag::kBanded && r.flagged_triangles[f] > sized.widest_flags.at(0)[f]) flags_ok = false;
    return r.error.footprint_max <= target.max_error && flags_ok &&
           double(r.cycles) <= max_slowdown * double(at_sized.cycles);
  };
  const DesignResult at_shrunk = evaluate(scene, design, shrunk.widths);
  EXPECT_TRUE(within(at_shrunk));
  EXPECT_EQ(at_shrunk.cycles, shrunk.results.at(0).cycles);
  EXPECT_EQ(at_shrunk.error.footprint_max, shrunk.error);
  if (depth / 2 >= 4) {
    Widths half = shrunk.widths;
    half.table_depth = depth / 2;
    EXPECT_FALSE(within(evaluate(scene, design, half))) << "a table of " << depth / 2 << " lines was within budget too";
  }
}

// choose's setup search: the multipliers it takes keep the scene within the
// budget and change nothing but the cycles (the arithmetic is the same), and
// every cheaper choice, run here on its own, is over the budget; a user's
// setup_multipliers stays.
// cd-linear sized for 0.5 footprints on the small scene, from the fully
// parallel setup engine (not copied: sized was run on &scene).
struct SmallSceneSizing {
  PreparedScene scene = prepare(load_scene(CDSIM_TEST_DATA "/small_scene.tri"), Widths{});
  const Design& design = find_design("cd-linear");
  ErrorTarget target{0.5, "footprint", "max"};
  Sizing sized = size_design(design, {&scene}, Widths{}, target);
};

TEST(Size, ShrinkSetupTakesTheFewestMultipliersWithinBudget) {
  const SmallSceneSizing sizing;
  const PreparedScene& scene = sizing.scene;
  const Design& design = sizing.design;
  const ErrorTarget& target = sizing.target;
  const Sizing& sized = sizing.sized;
  ASSERT_TRUE(sized.reachable);
  ASSERT_EQ(sized.widths.setup_multipliers, 0);
  const DesignResult at_sized = evaluate(scene, design, sized.widths);
  const std::vector<int> choices = setup_multiplier_choices();
  // On this scene M = 1, 2, 4, 8 cost about 0.5, 0.3, 0.16 and 0.13% more cycles than M = 0.
  for (const double max_slowdown : {1.0, 1.0015, 1.003, 1.02, 100.0}) {
    Sizing shrunk = sized;
    shrink_setup(design, {&scene}, target, max_slowdown, at_sized.cycles, shrunk);
    const int m = shrunk.widths.setup_multipliers;
    Widths others = shrunk.widths;
    others.setup_multipliers = 0;
    EXPECT_EQ(describe(others), describe(sized.widths)) << "only setup_multipliers changes";
    const DesignResult at_shrunk = evaluate(scene, design, shrunk.widths);
    EXPECT_EQ(at_shrunk.error.footprint_max, at_sized.error.footprint_max);
    EXPECT_EQ(at_shrunk.pixels, at_sized.pixels);
    EXPECT_LE(double(at_shrunk.cycles), max_slowdown * double(at_sized.cycles)) << "M = " << m;
    EXPECT_EQ(at_shrunk.cycles, shrunk.results.at(0).cycles);
    // Every choice before the one taken (all of them when none was) is over the budget.
    for (const int cheaper : choices) {
      if (cheaper == m) break;
      Widths trial = sized.widths;
      trial.setup_multipliers = cheaper;
      EXPECT_GT(double(evaluate(scene, design, trial).cycles), max_slowdown * double(at_sized.cycles))
          << "M = " << cheaper << " was within " << max_slowdown << " too";
    }
    if (max_slowdown >= 100.0) {
      EXPECT_EQ(m, choices.front()) << "any shared engine is within a budget of 100";
    }
  }
  Sizing user = sized;
  user.widths.setup_multipliers = 4;
  shrink_setup(design, {&scene}, target, 100.0, at_sized.cycles, user);
  EXPECT_EQ(user.widths.setup_multipliers, 4) << "the user's setup_multipliers stays";
}

// A rate target stops the shrinking where the cycle budget would not: every
// choice before the one taken runs the scene below the rate, and the one
// taken (or M = 0 when none) runs it at the rate or more.
TEST(Size, ShrinkSetupKeepsTheRate) {
  const SmallSceneSizing sizing;
  const PreparedScene& scene = sizing.scene;
  const Design& design = sizing.design;
  const ErrorTarget& target = sizing.target;
  const Sizing& sized = sizing.sized;
  ASSERT_TRUE(sized.reachable);
  const DesignResult parallel = evaluate(scene, design, sized.widths);
  const auto rate_at = [&](int m) {
    Widths trial = sized.widths;
    trial.setup_multipliers = m;
    return evaluate(scene, design, trial).pixels_per_clock();
  };
  const std::vector<int> choices = setup_multiplier_choices();
  // A rate between M = 1's and the fastest shared engine's, one above every
  // engine's (M = 0 stays), and none.
  const double between = (rate_at(choices.front()) + rate_at(choices.back())) / 2;
  for (const double min_rate : {between, 2 * parallel.pixels_per_clock(), 0.0}) {
    Sizing shrunk = sized;
    shrink_setup(design, {&scene}, target, 100.0, parallel.cycles, shrunk, min_rate);
    const int m = shrunk.widths.setup_multipliers;
    if (m != 0) {
      EXPECT_GE(rate_at(m), min_rate) << "M = " << m;
    }
    for (const int cheaper : choices) {
      if (cheaper == m) break;
      EXPECT_LT(rate_at(cheaper), min_rate) << "M = " << cheaper << " kept " << min_rate << " px/clk too";
    }
  }
  ASSERT_LT(rate_at(choices.front()), between) << "the scene must separate M = 1 from the fastest shared engine";
}

// model/designs.def's sized widths are the widths a design's accuracy
// depends on: against the evaluation itself, each one narrowed to its
// minimum on the default scene at a sixteenth of its pixels changes the
// design's error or cycles (eps_int, whose default is its minimum, has
// nothing narrower to try); and its sweep axes parse as a sweep file's.
TEST(DesignTable, EverySizedWidthMovesTheDesignsResults) {
  const Widths defaults;
  SceneOptions small;
  small.resolution = "480x270";
  const PreparedScene scene = prepare(load_scene("default", small), defaults);
  for (const Design& design : all_designs()) {
    ASSERT_FALSE(design.sized_widths.empty()) << design.name;
    ASSERT_FALSE(design.sweep_axes.empty()) << design.name;
    for (const std::string& axis : design.sweep_axes) EXPECT_NO_THROW(parse_axis(axis)) << design.name << " " << axis;
    const DesignResult base = evaluate(scene, design, defaults);
    for (const std::string& name : design.sized_widths) {
      const auto info = std::find_if(param_table().begin(), param_table().end(),
                                     [&](const ParamInfo& p) { return name == p.name; });
      ASSERT_NE(info, param_table().end()) << design.name << " sizes " << name;
      if (info->min_value == info->default_value) continue;
      const int value = info->min_value;
      Widths moved = defaults;
      set_param(moved, name, value);
      const DesignResult r = evaluate(scene, design, moved);
      EXPECT_TRUE(r.error.max != base.error.max || r.error.mean != base.error.mean || r.cycles != base.cycles)
          << design.name << ": " << name << " = " << value << " changes nothing";
    }
  }
}

// choose's pipelining steps (docs/choose.md): the correction adder's
// registers for a table design whose clock the adder or the control sets (2
// with persp, 1 without), twice the reciprocal's stages for the reciprocal (up
// to one quotient bit a stage),
// half the divider bits a cycle for the affine setup, for the setup engine
// the products' register or, on a path into a divider, half its bits a
// cycle, the fill's products' register for the paths into the table,
// nothing for a block without a knob, a knob spent or one the user set.
TEST(ChoosePipelining, OneStepOfTheBlockThatSetsTheClock) {
  const Widths w;
  const Design& persp = find_design("cd-persp");
  const Design& linear = find_design("cd-linear");
  const Design& divide = find_design("divide");
  ASSERT_TRUE(deeper_pipeline(persp, w, "control", {}).has_value());
  EXPECT_EQ(deeper_pipeline(persp, w, "control", {})->correction_stages, 2);
  EXPECT_EQ(deeper_pipeline(linear, w, "correction adder", {})->correction_stages, 1);
  Widths spent = w;
  spent.correction_stages = 1;
  EXPECT_FALSE(deeper_pipeline(linear, spent, "correction adder", {}).has_value());
  EXPECT_FALSE(deeper_pipeline(divide, w, "control", {}).has_value());
  EXPECT_FALSE(deeper_pipeline(persp, w, "control", {"correction_stages=0"}).has_value());
  ASSERT_TRUE(deeper_pipeline(divide, w, "reciprocal", {}).has_value());
  EXPECT_EQ(deeper_pipeline(divide, w, "reciprocal", {})->recip_latency, 2 * w.recip_latency);
  Widths deep = w;
  deep.recip_latency = 64;
  EXPECT_FALSE(deeper_pipeline(divide, deep, "reciprocal", {}).has_value());
  EXPECT_FALSE(deeper_pipeline(divide, w, "reciprocal", {"recip_latency=4"}).has_value());
  // Never past one quotient bit a stage (recip_bits + 1 stages): more would
  // be registers that cut no path.
  Widths short_recip = w;
  short_recip.recip_bits = 8;
  short_recip.recip_latency = 8;
  ASSERT_TRUE(deeper_pipeline(divide, short_recip, "reciprocal", {}).has_value());
  EXPECT_EQ(deeper_pipeline(divide, short_recip, "reciprocal", {})->recip_latency, 9);
  short_recip.recip_latency = 9;
  EXPECT_FALSE(deeper_pipeline(divide, short_recip, "reciprocal", {}).has_value());
  // The setup engine: a path into a stage's multiply-add takes the
  // products' register (one multiplier a product only); a path into one of
  // its serial dividers (an instance u_*_divider) half the bits a cycle.
  const std::string stage_end = "u_setup_engine/_c94709_/D";
  const std::string divider_end = "u_setup_engine/u_dividers.gen_edge_dividers[1].u_bound_divider/_c12_/D";
  ASSERT_TRUE(deeper_pipeline(persp, w, "setup engine", {}, stage_end).has_value());
  EXPECT_EQ(deeper_pipeline(persp, w, "setup engine", {}, stage_end)->setup_product_register, 1);
  EXPECT_EQ(deeper_pipeline(persp, w, "setup engine", {}, stage_end)->div_bits_per_cycle, w.div_bits_per_cycle);
  ASSERT_TRUE(deeper_pipeline(persp, w, "setup engine", {}, divider_end).has_value());
  EXPECT_EQ(deeper_pipeline(persp, w, "setup engine", {}, divider_end)->setup_product_register, 0);
  EXPECT_EQ(deeper_pipeline(persp, w, "setup engine", {}, divider_end)->div_bits_per_cycle, w.div_bits_per_cycle / 2);
  // Then (sums registered, or shared multipliers) stage D's line register.
  Widths registered = w;
  registered.setup_product_register = 1;
  ASSERT_TRUE(deeper_pipeline(linear, registered, "setup engine", {}, stage_end).has_value());
  EXPECT_EQ(deeper_pipeline(linear, registered, "setup engine", {}, stage_end)->setup_line_register, 1);
  Widths shared = w;
  shared.setup_multipliers = 2;
  ASSERT_TRUE(deeper_pipeline(linear, shared, "setup engine", {}, stage_end).has_value());
  EXPECT_EQ(deeper_pipeline(linear, shared, "setup engine", {}, stage_end)->setup_product_register, 0);
  EXPECT_EQ(deeper_pipeline(linear, shared, "setup engine", {}, stage_end)->setup_line_register, 1);
  EXPECT_EQ(deeper_pipeline(linear, w, "setup engine", {"setup_product_register=0"}, stage_end)->setup_line_register, 1);
  // A path into the multipliers' own registers (shared, or the registered
  // sums): a multiply, no step.
  const std::string multiplier_end = "u_setup_engine/u_multipliers/_c26763_";
  EXPECT_FALSE(deeper_pipeline(linear, shared, "setup engine", {}, multiplier_end).has_value());
  EXPECT_FALSE(deeper_pipeline(linear, w, "setup engine", {}, multiplier_end).has_value());
  Widths both = registered;
  both.setup_line_register = 1;
  EXPECT_FALSE(deeper_pipeline(linear, both, "setup engine", {}, stage_end).has_value());
  EXPECT_FALSE(deeper_pipeline(linear, registered, "setup engine", {"setup_line_register=0"}, stage_end).has_value());
  EXPECT_FALSE(deeper_pipeline(linear, w, "setup engine", {"div_bits_per_cycle=4"}, divider_end).has_value());
  // The paths into the table: the fill's products' register, table designs only.
  ASSERT_TRUE(deeper_pipeline(linear, w, "scanline table", {}).has_value());
  EXPECT_EQ(deeper_pipeline(linear, w, "scanline table", {})->fill_product_register, 1);
  Widths filled = w;
  filled.fill_product_register = 1;
  EXPECT_FALSE(deeper_pipeline(linear, filled, "scanline table", {}).has_value());
  EXPECT_FALSE(deeper_pipeline(linear, w, "scanline table", {"fill_product_register=0"}).has_value());
  EXPECT_FALSE(deeper_pipeline(divide, w, "scanline table", {}).has_value());
  const Design& affine = find_design("affine");
  ASSERT_TRUE(deeper_pipeline(affine, w, "affine setup", {}).has_value());
  EXPECT_EQ(deeper_pipeline(affine, w, "affine setup", {})->div_bits_per_cycle, w.div_bits_per_cycle / 2);
  Widths one_bit = w;
  one_bit.div_bits_per_cycle = 1;
  EXPECT_FALSE(deeper_pipeline(affine, one_bit, "affine setup", {}).has_value());
}

// A step that raises f_max is kept, whether or not one is on trial; the first
// that does not (equal or lower) goes on trial, and a second ends the search.
TEST(ChoosePipelining, AStepThatDoesNotRaiseTheClockGetsOneMoreOnTop) {
  EXPECT_EQ(pipelining_verdict(43.9, 50.8, false), PipeliningVerdict::Keep);
  EXPECT_EQ(pipelining_verdict(43.9, 50.8, true), PipeliningVerdict::Keep);
  EXPECT_EQ(pipelining_verdict(50.8, 50.0, false), PipeliningVerdict::Trial);
  EXPECT_EQ(pipelining_verdict(50.8, 50.8, false), PipeliningVerdict::Trial);
  EXPECT_EQ(pipelining_verdict(50.8, 50.0, true), PipeliningVerdict::Stop);
  EXPECT_EQ(pipelining_verdict(50.8, 50.8, true), PipeliningVerdict::Stop);
}

}  // namespace
}  // namespace cdsim
