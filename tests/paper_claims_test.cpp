// Han & Wang's claims, measured on the embedded default scene at default widths.
#include <gtest/gtest.h>

#include "evaluate.hpp"
#include "scene.hpp"

namespace cdsim {
namespace {

class DefaultScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const Widths w;
    const PreparedScene scene = prepare(default_scene(), w);
    for (const char* name : {"cd-none", "cd-linear", "divide"})
      results_[name] = evaluate(scene, find_design(name), w);
  }
  static inline std::map<std::string, DesignResult> results_;
};

TEST_F(DefaultScene, HasBothLineOrientations) {
  const DesignResult& r = results_.at("cd-none");
  EXPECT_GT(r.x_major_triangles, 100);
  EXPECT_GT(r.y_major_triangles, 100);
}

TEST_F(DefaultScene, NoCorrectionShowsTheOffLineError) {
  // A pixel sits up to half a line from the line whose value it takes, so its
  // error reaches about half its footprint, far above the divide baseline.
  const DesignResult& none = results_.at("cd-none");
  EXPECT_GT(none.error.footprint_max, 0.3);
  EXPECT_LT(none.error.footprint_max, 0.6);
  EXPECT_GT(none.error.mean, 100.0 * results_.at("divide").error.mean);
  EXPECT_GT(none.error.texel_mismatch, 0.10);
}

TEST_F(DefaultScene, LinearCorrectionCutsMeanErrorTenfold) {
  const double none = results_.at("cd-none").error.mean;
  const double linear = results_.at("cd-linear").error.mean;
  RecordProperty("mean_error_ratio", std::to_string(none / linear));
  EXPECT_GE(none / linear, 10.0) << "cd-none " << none << " cd-linear " << linear;
}

TEST_F(DefaultScene, EveryDesignDrawsTheSamePixels) {
  EXPECT_EQ(results_.at("cd-none").pixels, results_.at("divide").pixels);
  EXPECT_EQ(results_.at("cd-linear").pixels, results_.at("divide").pixels);
}

}  // namespace
}  // namespace cdsim
