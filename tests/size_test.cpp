// Sizing (app/size.cpp) against independent evaluations of the model.
#include <gtest/gtest.h>

#include "design.hpp"
#include "evaluate.hpp"
#include "scene.hpp"
#include "size.hpp"
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

}  // namespace
}  // namespace cdsim
