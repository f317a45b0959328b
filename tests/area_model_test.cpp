// The component area model's pieces that need no Yosys (app/area_model.cpp):
// the features of word-level cells, counted by hand here; the per-kind
// non-negative least squares, which must recover coefficients that generated
// the samples, must not see the configuration it leaves out and must satisfy
// the optimality conditions where the plain fit goes negative; and the random calibration
// widths, which must be valid, in range and reproducible.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <vector>

#include "area_detail.hpp"
#include "area_model.hpp"
#include "cache_files.hpp"
#include "widths.hpp"

#include <unistd.h>

#include <filesystem>

namespace {

using cdsim::AreaFeatures;
using cdsim::AreaSample;

// A Yosys JSON cell whose ports have the given bits: `live` net bits, then
// `constant` constant bits ("0").
nlohmann::json port(int live, int constant = 0) {
  nlohmann::json bits = nlohmann::json::array();
  for (int i = 0; i < live; ++i) bits.push_back(100 + i);
  for (int i = 0; i < constant; ++i) bits.push_back("0");
  return bits;
}

size_t feature(const char* name) {
  for (size_t i = 0; i < cdsim::kAreaFeatures.size(); ++i)
    if (std::string(cdsim::kAreaFeatures[i]) == name) return i;
  ADD_FAILURE() << "no feature " << name;
  return 0;
}

AreaFeatures features_of(const std::string& type, const nlohmann::json& connections) {
  AreaFeatures f{};
  cdsim::add_cell_features(type, {{"type", type}, {"connections", connections}}, f);
  return f;
}

TEST(AreaModel, MultiplierFeatureCountsThePartialProductBitsThatReachTheKeptProduct) {
  // 8 x 8 into 16 bits: all 64 partial-product bits.
  EXPECT_EQ(features_of("$mul", {{"A", port(8)}, {"B", port(8)}, {"Y", port(16)}})[feature("mul_pp_bits")], 64);
  // Into 8 bits: bit i of A meets bits 0 .. 7-i of B, 8+7+...+1 = 36.
  EXPECT_EQ(features_of("$mul", {{"A", port(8)}, {"B", port(8)}, {"Y", port(8)}})[feature("mul_pp_bits")], 36);
  // Constant bits of an operand make no partial products: 5 live x 3 live.
  EXPECT_EQ(features_of("$mul", {{"A", port(5, 3)}, {"B", port(3, 5)}, {"Y", port(16)}})[feature("mul_pp_bits")], 15);
}

TEST(AreaModel, EachCellTypeCountsInItsOwnFeature) {
  const auto only = [](const AreaFeatures& f, size_t index, double value) {
    for (size_t i = 0; i < f.size(); ++i) EXPECT_EQ(f[i], i == index ? value : 0.0) << cdsim::kAreaFeatures[i];
  };
  only(features_of("$add", {{"A", port(12)}, {"B", port(12)}, {"Y", port(13)}}), feature("add_bits"), 13);
  only(features_of("$lt", {{"A", port(9, 3)}, {"B", port(4)}, {"Y", port(1)}}), feature("compare_bits"), 9);
  only(features_of("$eq", {{"A", port(6)}, {"B", port(0, 6)}, {"Y", port(1)}}), feature("equal_bits"), 6);
  only(features_of("$mux", {{"A", port(10)}, {"B", port(10)}, {"S", port(1)}, {"Y", port(10)}}),
       feature("mux_bits"), 10);
  only(features_of("$pmux", {{"A", port(4)}, {"B", port(12)}, {"S", port(3)}, {"Y", port(4)}}),
       feature("pmux_bits"), 12);
  only(features_of("$sdffe", {{"D", port(7)}, {"Q", port(7)}}), feature("flop_bits"), 7);
  only(features_of("$adff", {{"D", port(5)}, {"Q", port(5)}}), feature("async_flop_bits"), 5);
  only(features_of("$shl", {{"A", port(16)}, {"B", port(4, 28)}, {"Y", port(16)}}), feature("shift_bits"), 64);
  only(features_of("$xor", {{"A", port(3)}, {"B", port(3)}, {"Y", port(3)}}), feature("logic_bits"), 3);
  only(features_of("$reduce_or", {{"A", port(20)}, {"Y", port(1)}}), feature("reduce_bits"), 20);
  // An adder with a constant operand (i + 1) is an incrementer, counted apart.
  only(features_of("$add", {{"A", port(12)}, {"B", port(0, 1)}, {"Y", port(13)}}), feature("const_add_bits"), 13);
  only(features_of("$sub", {{"A", port(0, 8)}, {"B", port(8)}, {"Y", port(8)}}), feature("const_add_bits"), 8);
  // A part-select of a constant vector is a ROM: its bits, not the index's.
  only(features_of("$shiftx", {{"A", port(0, 257 * 31)}, {"B", port(14)}, {"Y", port(31)}}), feature("rom_bits"),
       257 * 31);
  only(features_of("$shiftx", {{"A", port(40)}, {"B", port(3)}, {"Y", port(8)}}), feature("shift_bits"), 24);
}

// An archive of another elaboration flow keeps the syntheses of unchanged RTL
// and drops their inventories (to be elaborated again); other RTL is dropped.
TEST(AreaModel, ArchiveOfAnotherFlowKeepsTheSynthesesOfTheSameRtl) {
  const std::string old_flow = "coarse-flow-0";
  const nlohmann::json entry = {{"design", "divide"},
                                {"logic_area_um2", 1000.0},
                                {"flop_table_area_um2", 0.0},
                                {"own_area", {{"unit", {{"m", 1000.0}}}, {"table", nlohmann::json::object()}}},
                                {"inventory", {{"unit", nlohmann::json::object()}, {"table", nlohmann::json::object()}}}};
  nlohmann::json same = entry, other = entry;
  same["rtl_hash"] = cdsim::rtl_sources_hash(old_flow);
  other["rtl_hash"] = "0123456789abcdef";
  const std::string path = ::testing::TempDir() + "/old_flow_archive.json";
  {
    std::ofstream out(path);
    out << nlohmann::json{{"flow", old_flow}, {"configurations", {{"same", same}, {"other", other}}}}.dump();
  }
  const nlohmann::json kept = cdsim::load_area_archive(path);
  ASSERT_EQ(kept.size(), 1u);
  ASSERT_TRUE(kept.contains("same"));
  EXPECT_FALSE(kept.at("same").contains("inventory"));
  EXPECT_EQ(kept.at("same").at("rtl_hash"), cdsim::rtl_sources_hash());
  EXPECT_NE(cdsim::rtl_sources_hash(), cdsim::rtl_sources_hash(old_flow));
  EXPECT_EQ(kept.at("same").at("logic_area_um2"), 1000.0);
  std::remove(path.c_str());
}

// Samples of two kinds made by known coefficients (with a little noise): the
// fit must give them back, and must ignore the configuration it leaves out.
TEST(AreaModel, FitRecoversTheCoefficientsPerKindAndLeavesTheConfigurationOut) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> width(1, 60), noise(-1, 1);
  AreaFeatures truth_a{}, truth_b{};
  for (size_t i = 0; i < truth_a.size(); ++i) {
    truth_a[i] = 10.0 + 5.0 * static_cast<double>(i);
    truth_b[i] = 300.0 - 20.0 * static_cast<double>(i);
  }
  std::vector<AreaSample> samples;
  for (size_t config = 0; config < 40; ++config)
    for (const auto& [kind, truth] : {std::pair{"a", truth_a}, std::pair{"b", truth_b}}) {
      AreaSample s;
      s.kind = kind;
      s.config = config;
      for (double& f : s.features) f = std::round(width(rng));
      for (size_t i = 0; i < s.features.size(); ++i) s.area += truth[i] * s.features[i];
      s.area += noise(rng);
      samples.push_back(s);
    }
  // A wild sample in configuration 3: the fit without it must not feel it.
  samples.push_back({"a", samples[0].features, 1e9, 3});
  // Kind "c" has too few samples for a fit of its own (one short of two per
  // feature, all of them in use): it takes the fit of all kinds.
  for (size_t config = 0; config < cdsim::kSamplesPerFeature * cdsim::kAreaFeatures.size() - 1; ++config)
    samples.push_back({"c", samples[2 * config].features, samples[2 * config].area, config});
  const auto without = cdsim::fit_area_coefficients(samples, 3);
  ASSERT_EQ(without.size(), 3u);
  EXPECT_TRUE(without.count("a") && without.count("b") && without.count(cdsim::kAnyKind));
  for (size_t i = 0; i < truth_a.size(); ++i) {
    EXPECT_NEAR(without.at("a")[i], truth_a[i], 0.1) << cdsim::kAreaFeatures[i];
    EXPECT_NEAR(without.at("b")[i], truth_b[i], 0.1) << cdsim::kAreaFeatures[i];
  }
  const auto with = cdsim::fit_area_coefficients(samples, 1000);
  double moved = 0;
  for (size_t i = 0; i < truth_a.size(); ++i) moved += std::abs(with.at("a")[i] - truth_a[i]);
  EXPECT_GT(moved, 1000) << "the wild sample is in the fit that keeps configuration 3";
}

// Where the plain least-squares fit would give a feature negative area, the
// fit is the non-negative one: checked by its optimality conditions (Karush,
// Kuhn, Tucker) on the samples, not by another solver. A kind that uses only
// some features needs two samples per feature it uses, not per feature.
TEST(AreaModel, FitIsTheNonNegativeLeastSquaresOne) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> width(1, 60), noise(-400, 400);
  AreaFeatures truth{};
  for (size_t i = 0; i < truth.size(); i += 2) truth[i] = 20.0 + static_cast<double>(i);  // odd ones 0
  std::vector<AreaSample> samples;
  for (size_t config = 0; config < 30; ++config) {
    AreaSample s;
    s.kind = "d";
    s.config = config;
    for (double& f : s.features) f = std::round(width(rng));
    for (size_t i = 0; i < s.features.size(); ++i) s.area += truth[i] * s.features[i];
    s.area += noise(rng);
    samples.push_back(s);
  }
  // Kind "e" uses three features: six samples fit it on its own.
  for (size_t config = 0; config < 6; ++config) {
    AreaSample s;
    s.kind = "e";
    s.config = config;
    s.features[0] = static_cast<double>(config + 1);
    s.features[3] = static_cast<double>((config * 7) % 5 + 1);
    s.features[5] = static_cast<double>((config * 3) % 4 + 2);
    s.area = 5 * s.features[0] + 7 * s.features[3] + 11 * s.features[5];
    samples.push_back(s);
  }
  const auto fit = cdsim::fit_area_coefficients(samples, 1000);

  Eigen::MatrixXd x(30, static_cast<Eigen::Index>(truth.size()));
  Eigen::VectorXd y(30);
  for (Eigen::Index r = 0; r < 30; ++r) {
    for (Eigen::Index c = 0; c < x.cols(); ++c) x(r, c) = samples[static_cast<size_t>(r)].features[static_cast<size_t>(c)];
    y(r) = samples[static_cast<size_t>(r)].area;
  }
  const Eigen::VectorXd plain = x.householderQr().solve(y);
  ASSERT_LT(plain.minCoeff(), 0) << "the samples must make the plain fit negative somewhere";
  ASSERT_TRUE(fit.count("d"));
  Eigen::VectorXd beta(x.cols());
  for (Eigen::Index c = 0; c < x.cols(); ++c) beta(c) = fit.at("d")[static_cast<size_t>(c)];
  // KKT: beta >= 0; the gradient of the squared residual is zero where
  // beta > 0 and does not point into the feasible set where beta = 0.
  const Eigen::VectorXd gradient = x.transpose() * (x * beta - y);
  const double scale = (x.transpose() * y).cwiseAbs().maxCoeff();
  int zeros = 0;
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    EXPECT_GE(beta(c), 0) << cdsim::kAreaFeatures[static_cast<size_t>(c)];
    if (beta(c) > 0) EXPECT_NEAR(gradient(c) / scale, 0, 1e-9) << cdsim::kAreaFeatures[static_cast<size_t>(c)];
    else {
      ++zeros;
      EXPECT_GE(gradient(c) / scale, -1e-9) << cdsim::kAreaFeatures[static_cast<size_t>(c)];
    }
  }
  EXPECT_GT(zeros, 0) << "some feature is held at zero";
  ASSERT_TRUE(fit.count("e")) << "three features used, six samples: a fit of its own";
  EXPECT_NEAR(fit.at("e")[0], 5, 1e-6);
  EXPECT_NEAR(fit.at("e")[3], 7, 1e-6);
  EXPECT_NEAR(fit.at("e")[5], 11, 1e-6);
}

TEST(AreaModel, RandomWidthsAreValidInRangeAndReproducible) {
  std::vector<int> distinct_q;
  for (int i = 0; i < 50; ++i) {
    const cdsim::Widths w = cdsim::random_widths(1, "cd-linear", i);
    EXPECT_NO_THROW(cdsim::validate(w));
    for (const cdsim::ParamInfo& p : cdsim::param_table()) {
      EXPECT_GE(w.*(p.field), p.min_value) << p.name;
      EXPECT_LE(w.*(p.field), p.max_value) << p.name;
    }
    EXPECT_EQ(cdsim::describe(w), cdsim::describe(cdsim::random_widths(1, "cd-linear", i)));
    distinct_q.push_back(w.q_bits);
  }
  EXPECT_NE(cdsim::describe(cdsim::random_widths(1, "cd-linear", 0)),
            cdsim::describe(cdsim::random_widths(2, "cd-linear", 0)));
  EXPECT_NE(cdsim::describe(cdsim::random_widths(1, "cd-linear", 0)),
            cdsim::describe(cdsim::random_widths(1, "divide", 0)));
  std::sort(distinct_q.begin(), distinct_q.end());
  EXPECT_GT(std::unique(distinct_q.begin(), distinct_q.end()) - distinct_q.begin(), 10);
}

}  // namespace

// The area cache (app/area.cpp): a result that its manifest does not vouch
// for, or that makes no sense (a negative area), is said to be corrupt,
// naming the file, and built again; never printed.
// The widest multiply of each block: from Yosys's `dump t:$mul` after
// wreduce, per module, then over each block's subtree, the fill's reciprocal
// left to a block of its own. A hand-made hierarchy: the setup engine holds a
// 12 x 10 multiply, the shared-multiplier bank (8 x 8, 16 bits) and the
// reciprocal (20 x 20 = 40 bits, the widest of all, which is not the setup
// engine's); the walker holds none; the unit itself a 24 x 24 = 48 one.
TEST(AreaBlocks, TheWidestMultiplyOfEachBlockIsItsWidestProductInItsSubtree) {
  namespace ad = cdsim::area_detail;
  const std::string dump = R"(
autoidx 9
module $paramod$abc\setup_engine
  cell $mul $mul$a
    parameter \A_SIGNED 1
    parameter \A_WIDTH 12
    parameter \B_SIGNED 1
    parameter \B_WIDTH 10
    parameter \Y_WIDTH 22
    connect \A \a
  end
  cell $mul $mul$b
    parameter \A_WIDTH 30
    parameter \B_WIDTH 2
    parameter \Y_WIDTH 20
  end
end
module \setup_multipliers
  cell $mul $mul$c
    parameter \A_WIDTH 8
    parameter \B_WIDTH 8
    parameter \Y_WIDTH 16
  end
end
module $paramod$def\reciprocal
  cell $mul $mul$d
    parameter \A_WIDTH 20
    parameter \B_WIDTH 20
    parameter \Y_WIDTH 40
  end
end
module \cd_scan_unit
  cell $mul $mul$e
    parameter \A_WIDTH 24
    parameter \B_WIDTH 24
    parameter \Y_WIDTH 48
  end
end
)";
  const auto multiplies = ad::parse_multiplies(dump);
  ASSERT_EQ(multiplies.size(), 4u);
  EXPECT_EQ(multiplies.at("$paramod$abc\\setup_engine").product, 22);  // 22 bits beat 20
  EXPECT_EQ(multiplies.at("$paramod$abc\\setup_engine").a, 12);

  std::map<std::string, ad::ModuleStat> unit;
  unit["cd_scan_unit"].submodules = {{"$paramod$abc\\setup_engine", 1}, {"column_walker", 1}};
  unit["$paramod$abc\\setup_engine"].submodules = {{"setup_multipliers", 1}, {"$paramod$def\\reciprocal", 1}};
  unit["$paramod$abc\\setup_engine"].own_area = 100;
  unit["setup_multipliers"].own_area = 10;
  unit["$paramod$def\\reciprocal"].own_area = 5;
  unit["column_walker"].own_area = 7;
  ad::UnitConfig config;
  config.top = "cd_scan_unit";
  config.reciprocal_owner = "setup_engine";
  std::map<std::string, nlohmann::json> blocks;
  for (const auto& b : ad::block_areas(unit, config, "unit.log", multiplies))
    blocks[b.at("name").get<std::string>()] = b;
  ASSERT_EQ(blocks.size(), 4u);  // setup engine, column walker, control, reciprocal
  EXPECT_EQ(blocks.at("setup engine").at("area_um2"), 110.0);
  EXPECT_EQ(blocks.at("setup engine").at("mul_product_bits"), 22);
  EXPECT_EQ(blocks.at("setup engine").at("mul_b_bits"), 10);
  EXPECT_EQ(blocks.at("reciprocal").at("mul_product_bits"), 40);
  EXPECT_EQ(blocks.at("column walker").at("mul_product_bits"), 0);
  EXPECT_EQ(blocks.at("control").at("mul_a_bits"), 24);
  EXPECT_EQ(blocks.at("control").at("mul_product_bits"), 48);
}

TEST(AreaCache, ACorruptOrNonsensicalResultIsNamedAndNotUsed) {
  namespace fs = std::filesystem;
  namespace ad = cdsim::area_detail;
  const nlohmann::json good = {{"seconds", 3.5},
                               {"blocks", {{{"name", "control"}, {"area_um2", 120.0}, {"flops", 4},
                                            {"mul_a_bits", 0}, {"mul_b_bits", 0}, {"mul_product_bits", 0}}}},
                               {"flop_table_lines", 0},
                               {"flop_table_area_um2", 0.0},
                               {"timing", {{"critical_path_ns", 7.5},
                                           {"critical_path_from", "_1_"},
                                           {"critical_path_to", "_2_"},
                                           {"block_critical_path_ns", {{"control", 7.5}}}}}};
  EXPECT_EQ(ad::check_synthesis(good), "");
  nlohmann::json untimed = good;  // cached by a flow without timing
  untimed.erase("timing");
  EXPECT_EQ(ad::check_synthesis(untimed), "no 'timing'");
  nlohmann::json no_path = good;
  no_path["timing"]["block_critical_path_ns"]["control"] = 0.0;
  EXPECT_EQ(ad::check_synthesis(no_path), "timing: block 'control' has critical path 0.0");
  nlohmann::json negative = good;
  negative["blocks"][0]["area_um2"] = -5.0;
  EXPECT_EQ(ad::check_synthesis(negative), "block 'control': 'area_um2' is -5.0, not a finite number >= 0");
  nlohmann::json missing = good;
  missing.erase("seconds");
  EXPECT_EQ(ad::check_synthesis(missing), "no 'seconds'");

  const fs::path cache = fs::temp_directory_path() / ("cdsim_area_cache_test_" + std::to_string(::getpid()));
  fs::remove_all(cache);
  ad::UnitConfig config;
  config.dir = cache / "0123456789abcdef";
  config.header = "// header\n";
  fs::create_directories(cache);
  int built = 0;
  const auto build = [&](const nlohmann::json& result) {
    ad::build_result(config, "result.json", [&](const fs::path& work) {
      ++built;
      cdsim::write_file_atomic(work / "unit.log", "log\n");
      cdsim::write_file_atomic(work / "result.json", result.dump());
    });
  };
  build(good);
  EXPECT_EQ(ad::cached_result(config, "result.json", ad::check_synthesis), good);
  // Only the entry and its lock-free files: the work folder is gone.
  for (const auto& entry : fs::directory_iterator(cache)) EXPECT_EQ(entry.path(), config.dir);

  testing::internal::CaptureStderr();
  cdsim::write_file_atomic(config.dir / "result.json", "{\"seconds\": ");  // truncated
  EXPECT_FALSE(ad::cached_result(config, "result.json", ad::check_synthesis).has_value());
  std::string said = testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("the cached " + (config.dir / "result.json").string() + " is corrupt"), std::string::npos) << said;
  EXPECT_FALSE(fs::exists(config.dir / "result.json"));

  build(negative);  // a manifest that vouches for it: the content is still checked
  testing::internal::CaptureStderr();
  EXPECT_FALSE(ad::cached_result(config, "result.json", ad::check_synthesis).has_value());
  said = testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("'area_um2' is -5.0"), std::string::npos) << said;

  // A failed build leaves no work folder, and keeps its logs apart.
  EXPECT_THROW(ad::build_result(config, "result.json",
                                [&](const fs::path& work) {
                                  cdsim::write_file_atomic(work / "unit.log", "ERROR\n");
                                  throw std::runtime_error("yosys failed: " + (work / "unit.log").string());
                                }),
               std::runtime_error);
  for (const auto& entry : fs::directory_iterator(cache))
    EXPECT_NE(entry.path().filename().string().rfind("tmp-", 0), 0u) << entry.path();
  EXPECT_TRUE(fs::exists(cache / "failed-0123456789abcdef" / "unit.log"));
  fs::remove_all(cache);
}
