// Static timing (app/sta.cpp) on netlists whose paths are known from the
// liberty by hand: a flip-flop, a chain of K inverters, a flip-flop, written
// here in osu018 cells and timed by OpenSTA through cdsim's own script and
// parser. The bands are read off osu018_stdcells.lib, not off OpenSTA:
//  - DFFPOSX1: clock to Q 0.094-0.17 ns (cell_rise and cell_fall at loads of
//    0.005-0.0125 pF and the fastest clock), setup 0.17-0.29 ns (setup_rising
//    at transitions up to 0.3 ns), so a direct flip-flop to flip-flop path
//    needs 0.26-0.46 ns: the band is 0.25-0.50.
//  - INVX1 driving one INVX1 input (0.0093 pF, between the tables' 0.005 and
//    0.0125 pF rows) at the first transition column: cell_fall 0.031-0.045 ns,
//    cell_rise 0.038-0.053 ns, so each inverter of a chain adds 0.030-0.060.
// And what a designer relies on: a flip-flop in the middle of the chain
// halves its path, and each path is counted in the block of the module that
// holds its end.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <tuple>

#include "area_detail.hpp"
#include "area_recovery.hpp"
#include "cache_files.hpp"
#include "netlist_writer.hpp"
#include "sta.hpp"

namespace {

namespace fs = std::filesystem;

constexpr const char* kLiberty = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib";

class Sta : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("cdsim_sta_test_" + std::to_string(::getpid()) + "_" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // launch -> K inverters -> capture; with `pipelined`, a third flip-flop
  // after the first K / 2 inverters. In module `sub` when `wrap` is given,
  // instanced as u_sub in the top.
  cdsim::StaReport time_chain(int k, bool pipelined, const std::string& wrap = "", double over_ns = 0) {
    std::string body;
    body += "  DFFPOSX1 launch (.CLK(clk_i), .D(d_i), .Q(n0));\n";
    for (int i = 1; i <= k; ++i) {
      const std::string in = pipelined && i == k / 2 + 1 ? "p" : "n" + std::to_string(i - 1);
      body += "  INVX1 inv" + std::to_string(i) + " (.A(" + in + "), .Y(n" + std::to_string(i) + "));\n";
    }
    if (pipelined) body += "  DFFPOSX1 pipe (.CLK(clk_i), .D(n" + std::to_string(k / 2) + "), .Q(p));\n";
    body += "  DFFPOSX1 capture (.CLK(clk_i), .D(n" + std::to_string(k) + "), .Q(q_o));\n";
    std::string wires = "  wire p";
    for (int i = 0; i <= k; ++i) wires += ", n" + std::to_string(i);
    wires += ";\n";
    const std::string ports = "(clk_i, d_i, q_o);\n  input clk_i;\n  input d_i;\n  output q_o;\n";
    std::string netlist;
    if (wrap.empty()) {
      netlist = "module chain" + ports + wires + body + "endmodule\n";
    } else {
      netlist = "module " + wrap + ports + wires + body + "endmodule\n" + "module chain" + ports +
                "  " + wrap + " u_sub (.clk_i(clk_i), .d_i(d_i), .q_o(q_o));\nendmodule\n";
    }
    const fs::path file = dir_ / "chain.v";
    cdsim::write_file_atomic(file, netlist);
    return cdsim::time_netlist({file}, "chain", kLiberty, "clk_i", dir_, over_ns);
  }

  fs::path dir_;
};

TEST_F(Sta, FlopToFlopIsClockToQPlusSetup) {
  const cdsim::StaReport r = time_chain(0, false);
  ASSERT_EQ(r.endpoints.size(), 1u) << "only capture's input is reached from a flip-flop";
  EXPECT_EQ(r.endpoints[0].pin, "capture/D");
  EXPECT_GE(r.endpoints[0].period_ns, 0.25);
  EXPECT_LE(r.endpoints[0].period_ns, 0.50);
  EXPECT_EQ(r.worst_from, "launch");
  EXPECT_EQ(r.worst_to, "capture");
}

TEST_F(Sta, EachInverterAddsItsLibertyDelay) {
  const double t16 = time_chain(16, false).endpoints.at(0).period_ns;
  const double t64 = time_chain(64, false).endpoints.at(0).period_ns;
  const double per_inverter = (t64 - t16) / 48;
  EXPECT_GE(per_inverter, 0.030) << t16 << " ns with 16, " << t64 << " ns with 64";
  EXPECT_LE(per_inverter, 0.060) << t16 << " ns with 16, " << t64 << " ns with 64";
}

TEST_F(Sta, APipelineRegisterHalvesThePath) {
  const double whole = time_chain(64, false).endpoints.at(0).period_ns;
  const double half = time_chain(32, false).endpoints.at(0).period_ns;
  const cdsim::StaReport cut = time_chain(64, true);
  ASSERT_EQ(cut.endpoints.size(), 2u) << "the pipeline register and capture";
  EXPECT_NEAR(cut.endpoints[0].period_ns, half, 0.05);
  EXPECT_LT(cut.endpoints[0].period_ns, whole - 32 * 0.030);
}

TEST_F(Sta, APathCountsInTheBlockThatHoldsItsEnd) {
  const cdsim::StaReport r = time_chain(8, false, "column_walker");
  ASSERT_EQ(r.endpoints.size(), 1u);
  EXPECT_EQ(r.endpoints[0].pin, "u_sub/capture/D");
  EXPECT_EQ(r.instance_module.at("u_sub"), "column_walker");
  EXPECT_EQ(cdsim::area_detail::block_of_pin(r.instance_module, r.endpoints[0].pin), "column walker");
  EXPECT_EQ(cdsim::area_detail::block_of_pin(r.instance_module, "capture/D"), "control");
}

// The recovering flow's input: the logic cells of the paths over a period,
// by their hierarchical names, the flip-flops left out.
TEST_F(Sta, APathOverThePeriodListsItsLogicCells) {
  const cdsim::StaReport over = time_chain(8, false, "column_walker", 0.1);
  ASSERT_EQ(over.over_paths.size(), 1u);
  ASSERT_EQ(over.over_paths[0].size(), 8u) << "the eight inverters, not the two flip-flops";
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(over.over_paths[0][static_cast<size_t>(i)].first, "u_sub/inv" + std::to_string(i + 1));
    EXPECT_EQ(over.over_paths[0][static_cast<size_t>(i)].second, "INVX1");
  }
  EXPECT_EQ(cdsim::module_of_cell(over, "u_sub/inv1", "chain"), "column_walker");
  EXPECT_EQ(cdsim::module_of_cell(over, "inv1", "chain"), "chain");
  EXPECT_THROW(cdsim::module_of_cell(over, "u_none/inv1", "chain"), std::runtime_error);
  const double path = over.endpoints.at(0).period_ns;
  EXPECT_TRUE(time_chain(8, false, "column_walker", path + 0.01).over_paths.empty()) << "a path " << path << " ns";
  EXPECT_TRUE(time_chain(8, false, "column_walker").over_paths.empty()) << "not asked for";
}

TEST_F(Sta, AnUnknownCellIsAnErrorNotABlackBox) {
  cdsim::write_file_atomic(dir_ / "bad.v", "module chain(clk_i);\n  input clk_i;\n  NOSUCHCELL u (.A(clk_i));\nendmodule\n");
  try {
    cdsim::time_netlist({dir_ / "bad.v"}, "chain", kLiberty, "clk_i", dir_);
    FAIL() << "timed a netlist of an unknown cell";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("sta.log"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("NOSUCHCELL"), std::string::npos) << e.what();
  }
}

// cdsim area writes the netlist OpenSTA times from Yosys's JSON
// (app/netlist_writer.cpp); Yosys's own write_verilog is the oracle: a small
// synthesised design of two modules (a registered adder in a submodule, a
// constant output, an input passed straight to an output), written both ways,
// must time the same, endpoint by endpoint, with the same hierarchy.
TEST_F(Sta, TheJsonNetlistTimesAsYosysVerilog) {
  cdsim::write_file_atomic(dir_ / "design.v",
                           "module adder(input clk_i, input [7:0] a_i, input [7:0] b_i, output reg [8:0] s_o);\n"
                           "  reg [7:0] a, b;\n"
                           "  always @(posedge clk_i) begin a <= a_i; b <= b_i; s_o <= a + b; end\n"
                           "endmodule\n"
                           "module top(input clk_i, input [7:0] a_i, input [7:0] b_i, input pass_i,\n"
                           "           output [8:0] s_o, output zero_o, output pass_o);\n"
                           "  adder u_adder (.clk_i(clk_i), .a_i(a_i), .b_i(b_i), .s_o(s_o));\n"
                           "  assign zero_o = 1'b0;\n"
                           "  assign pass_o = pass_i;\n"
                           "endmodule\n");
  const std::string script = "read_verilog " + (dir_ / "design.v").string() +
                             "; hierarchy -top top; proc; opt; techmap; opt; dfflibmap -liberty " + kLiberty +
                             "; abc -liberty " + kLiberty + "; opt_clean; setundef -zero; splitnets -ports;"
                             " opt_clean -purge; write_json " + (dir_ / "design.json").string() +
                             "; write_verilog -noattr -noexpr -nohex -nodec " + (dir_ / "yosys.v").string();
  ASSERT_EQ(std::system(("yosys -q -p '" + script + "' > " + (dir_ / "yosys.log").string() + " 2>&1").c_str()), 0)
      << "see " << (dir_ / "yosys.log").string();
  cdsim::write_verilog_from_yosys_json(dir_ / "design.json", dir_ / "cdsim.v");
  fs::create_directories(dir_ / "y");
  fs::create_directories(dir_ / "c");
  const cdsim::StaReport yosys = cdsim::time_netlist({dir_ / "yosys.v"}, "top", kLiberty, "clk_i", dir_ / "y");
  const cdsim::StaReport ours = cdsim::time_netlist({dir_ / "cdsim.v"}, "top", kLiberty, "clk_i", dir_ / "c");
  EXPECT_EQ(ours.instance_module, yosys.instance_module);
  EXPECT_EQ(ours.instance_module.count("u_adder"), 1u);
  // The adder's nine sum flip-flops are reached by paths; the auto-named ones
  // are named differently, so the endpoints are compared as (module, delay).
  ASSERT_GE(yosys.endpoints.size(), 9u);
  ASSERT_EQ(ours.endpoints.size(), yosys.endpoints.size());
  for (size_t i = 0; i < ours.endpoints.size(); ++i)
    EXPECT_DOUBLE_EQ(ours.endpoints[i].period_ns, yosys.endpoints[i].period_ns) << "endpoint " << i;
  EXPECT_GT(yosys.endpoints.front().period_ns, 0.5) << "an 8-bit carry chain between two flip-flops";
}

// The recovering flow (app/area_recovery.cpp) on a design of two registered
// adders in modules of their own, mapped by the flow's two ABC scripts: a wide
// one, whose path sets the clock, and a narrow one with slack. The oracle is
// OpenSTA on each mapping alone: the area mapping must slow the wide adder
// (else there is nothing to recover), the chosen netlist must keep the delay
// mapping's clock, and the narrow adder, which has the slack, must take the
// area mapping.
class Recovery : public Sta {
 protected:
  // `design`.v mapped both ways: delay.json and area.json.
  void map_both(const std::string& verilog) {
    cdsim::write_file_atomic(dir_ / "design.v", verilog);
    cdsim::area_detail::write_abc_script(dir_, 0);
    cdsim::area_detail::write_area_abc_script(dir_);
    const auto tail = [&](const std::string& script, const std::string& json) {
      return "abc -liberty " + std::string(kLiberty) + " -script " + (dir_ / script).string() +
             "; opt_clean; setundef -zero; splitnets -ports; opt_clean -purge; write_json " +
             (dir_ / json).string() + "; ";
    };
    const std::string script = "read_verilog " + (dir_ / "design.v").string() +
                               "; hierarchy -top top; proc; opt -fast; wreduce; alumacc; opt -fast; techmap; "
                               "dfflibmap -liberty " + kLiberty + "; design -save flops; " +
                               tail("abc.script", "delay.json") + "design -load flops; " +
                               tail("abc_area.script", "area.json");
    ASSERT_EQ(std::system(("yosys -q -p '" + script + "' > " + (dir_ / "yosys.log").string() + " 2>&1").c_str()), 0)
        << "see " << (dir_ / "yosys.log").string();
    delay_ = cdsim::verilog_modules_from_yosys_json(nlohmann::json::parse(cdsim::read_text_file(dir_ / "delay.json")));
    area_ = cdsim::verilog_modules_from_yosys_json(nlohmann::json::parse(cdsim::read_text_file(dir_ / "area.json")));
  }
  // One mapping alone, timed.
  cdsim::StaReport time_alone(const cdsim::ModuleTexts& modules, const std::string& name) {
    fs::create_directories(dir_ / name);
    cdsim::write_file_atomic(dir_ / name / "unit.v", cdsim::verilog_from_modules(modules));
    return cdsim::time_netlist({dir_ / name / "unit.v"}, "top", kLiberty, "clk_i", dir_ / name);
  }
  static std::string adder(const std::string& name, int bits) {
    const std::string w = std::to_string(bits - 1);
    return "module " + name + "(input clk_i, input [" + w + ":0] a_i, input [" + w + ":0] b_i, output reg [" +
           std::to_string(bits) + ":0] s_o);\n  reg [" + w + ":0] a, b;\n"
           "  always @(posedge clk_i) begin a <= a_i; b <= b_i; s_o <= a + b; end\nendmodule\n";
  }
  static std::string two_adders() {
    return adder("wide", 48) + adder("narrow", 4) +
           "module top(input clk_i, input [47:0] a_i, input [47:0] b_i, output [48:0] w_o, output [4:0] n_o);\n"
           "  wide u_wide (.clk_i(clk_i), .a_i(a_i), .b_i(b_i), .s_o(w_o));\n"
           "  narrow u_narrow (.clk_i(clk_i), .a_i(a_i[3:0]), .b_i(b_i[3:0]), .s_o(n_o));\nendmodule\n";
  }
  cdsim::ModuleTexts delay_, area_;
};

TEST_F(Recovery, TheModuleWithSlackTakesTheAreaMappingAndTheClockStays) {
  map_both(two_adders());
  const double delay_ns = time_alone(delay_, "delay").endpoints.at(0).period_ns;
  const cdsim::StaReport area_alone = time_alone(area_, "area");
  ASSERT_GT(area_alone.endpoints.at(0).period_ns, delay_ns + 0.1)
      << "the area mapping does not slow the wide adder: nothing for the test to recover";
  EXPECT_EQ(cdsim::area_detail::block_of_pin(area_alone.instance_module, area_alone.endpoints.at(0).pin), "wide");
  fs::create_directories(dir_ / "mixed");
  const cdsim::Recovery r = cdsim::recover_area(delay_, area_, 0, "top", kLiberty, "clk_i", dir_ / "mixed");
  EXPECT_DOUBLE_EQ(r.target_ns, delay_ns);
  EXPECT_EQ(r.modules, 3u);
  EXPECT_FALSE(r.fell_back);
  EXPECT_EQ(r.area_modules.count("narrow"), 1u);
  EXPECT_EQ(r.area_modules.count("wide"), 0u);
  EXPECT_LE(r.chosen.endpoints.at(0).period_ns, delay_ns * 1.005 + 0.001);
  EXPECT_GE(r.rounds, 2) << "the first round, all area-mapped, is over the target";
  // The chosen netlist as written: the wide adder's text is the delay mapping's.
  const std::string chosen = cdsim::read_text_file(dir_ / "mixed" / "unit.v");
  for (const auto& [name, text] : delay_) {
    if (name == "wide") {
      EXPECT_NE(chosen.find(text), std::string::npos);
    }
  }
  for (const auto& [name, text] : area_) {
    if (name == "narrow") {
      EXPECT_NE(chosen.find(text), std::string::npos);
    }
  }
}

TEST_F(Recovery, ATargetNoMappingMeetsTakesTheDelayMappingEverywhere) {
  map_both(two_adders());
  fs::create_directories(dir_ / "mixed");
  const cdsim::Recovery r = cdsim::recover_area(delay_, area_, 0.05, "top", kLiberty, "clk_i", dir_ / "mixed");
  EXPECT_EQ(r.area_modules.count("wide") + r.area_modules.count("narrow"), 0u)
      << "every cell is on a path over 0.05 ns";
  EXPECT_DOUBLE_EQ(r.chosen.endpoints.at(0).period_ns, r.delay.endpoints.at(0).period_ns);
}

TEST_F(Recovery, TwoMappingsOfDifferentModulesAreRefused) {
  map_both(two_adders());
  cdsim::ModuleTexts fewer = area_;
  fewer.pop_back();
  EXPECT_THROW(cdsim::recover_area(delay_, fewer, 0, "top", kLiberty, "clk_i", dir_), std::runtime_error);
}

}  // namespace
