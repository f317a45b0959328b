// SystemC harness of the Verilated scan unit: a source that feeds triangles
// through the ready/valid input, a sink with random back-pressure, and the
// scoreboard seam (scoreboard.hpp) between them and the C++ model. Sampling and
// driving happen on the falling clock edge, so every value the harness reads
// is the settled state of the cycle, and every value it writes is what the
// unit samples at the next rising edge.
#include "regress.hpp"

#include "loaders/scene_cli.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <systemc.h>
#include <verilated.h>
#include <verilated_fst_sc.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <random>

#include "Vcd_scan_unit_default.h"
#include "Vcd_scan_unit_narrow.h"
#include "Vcd_scan_unit_wide.h"
#include "evaluate.hpp"
#include "random_triangles.hpp"
#include "scene.hpp"
#include "scoreboard.hpp"

// SystemC's library refers to sc_main; cdsim has its own main and starts the
// kernel itself, so this one is never called.
int sc_main(int, char**) { return 1; }

namespace cdsim::rtl {

namespace {

struct Options {
  std::string scene = "default";
  SceneOptions scene_options;
  size_t random = 0;
  uint64_t seed = 1;
  double backpressure = 0.0;
  std::string trace;
  std::string widths = "default";
  std::string design = "mix";
  int64_t only = -1;
};
Options options;

struct WidthConfig {
  const char* name;
  const char* settings;  // overrides of model/widths.def, "name=value ..."
};
const WidthConfig kConfigs[] = {
#define X(name, settings) {#name, settings},
#include "rtl_configs.def"
#undef X
};

Widths widths_of(const std::string& config) {
  for (const auto& c : kConfigs) {
    if (config != c.name) continue;
    Widths widths;
    std::string settings = c.settings;
    size_t start = 0;
    while (start < settings.size()) {
      size_t end = settings.find(' ', start);
      if (end == std::string::npos) end = settings.size();
      if (end > start) apply_setting(widths, settings.substr(start, end - start));
      start = end + 1;
    }
    validate(widths);
    return widths;
  }
  std::string known;
  for (const auto& c : kConfigs) known += fmt::format(" {}", c.name);
  throw std::invalid_argument(
      fmt::format("unknown width configuration '{}'; built:{}", config, known));
}

uint64_t mix_seed(uint64_t seed, uint64_t index) {
  uint64_t z = seed + 0x9e3779b97f4a7c15ull * (index + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

template <class Dut>
class Bench : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Bench);

  Bench(sc_core::sc_module_name name, const std::vector<Job>& jobs, Scoreboard& scoreboard)
      : sc_module(name), clk("clk", 10, sc_core::SC_NS), dut("dut"), jobs_(jobs),
        scoreboard_(scoreboard) {
    dut.clk_i(clk);
    dut.rst_ni(rst_n);
    dut.tri_valid_i(tri_valid);
    dut.tri_ready_o(tri_ready);
    dut.tri_x0_i(tri_x[0]); dut.tri_y0_i(tri_y[0]); dut.tri_q0_i(tri_q[0]);
    dut.tri_u0_i(tri_u[0]); dut.tri_v0_i(tri_v[0]);
    dut.tri_x1_i(tri_x[1]); dut.tri_y1_i(tri_y[1]); dut.tri_q1_i(tri_q[1]);
    dut.tri_u1_i(tri_u[1]); dut.tri_v1_i(tri_v[1]);
    dut.tri_x2_i(tri_x[2]); dut.tri_y2_i(tri_y[2]); dut.tri_q2_i(tri_q[2]);
    dut.tri_u2_i(tri_u[2]); dut.tri_v2_i(tri_v[2]);
    dut.viewport_width_i(viewport_width);
    dut.viewport_height_i(viewport_height);
    dut.density_log2_i(density_log2);
    dut.correction_i(correction);
    dut.frag_valid_o(frag_valid);
    dut.frag_ready_i(frag_ready);
    dut.frag_x_o(frag_x);
    dut.frag_y_o(frag_y);
    dut.frag_u_o(frag_u);
    dut.frag_v_o(frag_v);
    dut.frag_flags_o(frag_flags);
    dut.rec_valid_o(rec_valid);
    dut.rec_ready_i(rec_ready);
    dut.rec_cycles_o(rec_cycles);
    dut.rec_lines_o(rec_lines);
    dut.rec_bands_o(rec_bands);
    dut.rec_pixels_o(rec_pixels);
    dut.rec_flags_o(rec_flags);
    dut.obs_setup_valid_o(obs_setup_valid);
    dut.obs_setup_bits_o(obs_setup_bits);
    dut.obs_setup_g_o(obs_setup_g);
    dut.obs_setup_box_o(obs_setup_box);
    dut.obs_setup_lines_o(obs_setup_lines);
    dut.obs_write_valid_o(obs_write_valid);
    dut.obs_write_addr_o(obs_write_addr);
    dut.obs_write_tu_o(obs_write_tu);
    dut.obs_write_tv_o(obs_write_tv);
    dut.obs_write_su_o(obs_write_su);
    dut.obs_write_sv_o(obs_write_sv);
    dut.obs_write_flags_o(obs_write_flags);
    SC_METHOD(on_falling_edge);
    sensitive << clk.negedge_event();
    dont_initialize();
  }

  // Replays one triangle (after a mismatch, with the waveform on).
  void replay(size_t index) {
    replay_ = true;
    next_job_ = index;
    last_job_ = index + 1;
    failed_ = false;
  }

  bool failed() const { return failed_; }
  size_t failed_index() const { return failed_index_; }
  bool hung() const { return hung_; }
  int64_t clock_cycles() const { return clock_cycles_; }
  size_t triangles_done() const { return triangles_done_; }

  sc_core::sc_clock clk;
  Dut dut;

 private:
  void on_falling_edge() {
    ++clock_cycles_;
    if (reset_cycles_ > 0) {
      rst_n.write(false);
      rec_ready.write(true);
      if (--reset_cycles_ == 0) rst_n.write(true);
      return;
    }
    // Sink: the fragment taken at the coming rising edge, if any.
    const bool ready =
        !(options.backpressure > 0 && stall_dist_(stall_rng_) < options.backpressure);
    frag_ready.write(ready);
    if (frag_valid.read()) {
      if (!ready) {
        ++stalls_;
      } else if (checking_) {
        RtlFragment f;
        f.x = static_cast<int64_t>(frag_x.read());
        f.y = static_cast<int64_t>(frag_y.read());
        f.u = static_cast<int64_t>(frag_u.read());
        f.v = static_cast<int64_t>(frag_v.read());
        f.flags = frag_flags.read();
        if (!scoreboard_.fragment(f)) fail();
      }
    }
    if (checking_ && obs_setup_valid.read()) {
      const uint32_t bits = obs_setup_bits.read();
      const uint64_t box = obs_setup_box.read(), lines = obs_setup_lines.read();
      RtlSetup a;
      a.empty = bits & 1;
      a.x_major = (bits >> 1) & 1;
      a.no_lines = (bits >> 2) & 1;
      a.depth_range = (bits >> 3) & 1;
      a.g = static_cast<int32_t>(obs_setup_g.read());
      a.major_lo = static_cast<int64_t>((box >> 48) & 0xffff);
      a.major_count = static_cast<int64_t>((box >> 32) & 0xffff);
      a.minor_lo = static_cast<int64_t>((box >> 16) & 0xffff);
      a.minor_hi = static_cast<int64_t>(box & 0xffff);
      a.pixel_line_lo = static_cast<int32_t>(static_cast<uint32_t>(lines >> 32));
      a.pixel_line_hi = static_cast<int32_t>(static_cast<uint32_t>(lines));
      if (!scoreboard_.setup(a)) fail();
    }
    if (checking_ && obs_write_valid.read()) {
      RtlTableWrite w;
      w.address = obs_write_addr.read();
      w.t_u = static_cast<int64_t>(obs_write_tu.read());
      w.t_v = static_cast<int64_t>(obs_write_tv.read());
      w.s_u = static_cast<int64_t>(obs_write_su.read());
      w.s_v = static_cast<int64_t>(obs_write_sv.read());
      w.saturated = obs_write_flags.read() & 1;
      w.depth_range = (obs_write_flags.read() >> 1) & 1;
      if (!scoreboard_.table_write(w)) fail();
    }
    if (in_flight_ && ++busy_cycles_ > cycle_limit_) {
      std::cout << fmt::format("HANG seed {} triangle {}: no record after {} cycles\n  triangle {}\n",
                               options.seed, current_, busy_cycles_, describe_job(jobs_[current_]));
      hung_ = true;
      sc_core::sc_pause();
      return;
    }
    if (rec_valid.read()) {
      RtlRecord r;
      r.cycles = static_cast<int64_t>(rec_cycles.read());
      r.lines = rec_lines.read();
      r.bands = rec_bands.read();
      r.pixels = rec_pixels.read();
      r.flags = rec_flags.read();
      if (checking_ && !scoreboard_.record(r, stalls_)) fail();
      in_flight_ = false;
      ++triangles_done_;
      if (failed_ || replay_) {
        tri_valid.write(false);
        sc_core::sc_pause();
        return;
      }
    }
    // Source: offer the next triangle; it is taken at the coming rising edge
    // when the unit is ready.
    if (!presenting_ && !in_flight_ && next_job_ < last_job_) {
      const Job& job = jobs_[next_job_];
      for (size_t i = 0; i < 3; ++i) {
        const UnitVertex& v = job.triangle.vertex[i];
        tri_x[i].write(static_cast<uint32_t>(v.x));
        tri_y[i].write(static_cast<uint32_t>(v.y));
        tri_q[i].write(v.q_float);
        tri_u[i].write(static_cast<uint32_t>(v.u));
        tri_v[i].write(static_cast<uint32_t>(v.v));
      }
      viewport_width.write(static_cast<uint32_t>(job.viewport_width));
      viewport_height.write(static_cast<uint32_t>(job.viewport_height));
      density_log2.write(job.design->density == 4 ? 2u : job.design->density == 2 ? 1u : 0u);
      correction.write(job.design->correction);
      tri_valid.write(true);
      presenting_ = true;
      current_ = next_job_++;
      if (checking_) scoreboard_.begin(current_, job);
    } else {
      tri_valid.write(presenting_);
    }
    if (presenting_ && tri_ready.read()) {
      // Accepted at the coming edge: its stalls and back-pressure start now,
      // from a generator seeded by the triangle, so that a replay is identical.
      presenting_ = false;
      in_flight_ = true;
      stalls_ = 0;
      busy_cycles_ = 0;
      cycle_limit_ = 10'000'000;
      stall_rng_.seed(mix_seed(options.seed, current_));
    } else if (!presenting_ && !in_flight_) {
      tri_valid.write(false);
      if (next_job_ >= last_job_) sc_core::sc_pause();
    }
  }

  void fail() {
    if (!failed_) {
      failed_ = true;
      failed_index_ = current_;
      std::cout << scoreboard_.mismatch() << '\n';
    }
    checking_ = replay_;  // drain the failing triangle without further checks
  }

  sc_core::sc_signal<bool> rst_n{"rst_n"}, tri_valid{"tri_valid"}, tri_ready{"tri_ready"};
  sc_core::sc_signal<uint32_t> tri_x[3], tri_y[3], tri_q[3], tri_u[3], tri_v[3];
  sc_core::sc_signal<uint32_t> viewport_width, viewport_height, density_log2;
  sc_core::sc_signal<bool> correction, frag_valid, frag_ready, rec_valid, rec_ready;
  sc_core::sc_signal<uint32_t> frag_x, frag_y, frag_flags;
  sc_core::sc_signal<uint64_t> frag_u, frag_v, rec_cycles;
  sc_core::sc_signal<uint32_t> rec_lines, rec_bands, rec_pixels, rec_flags;
  sc_core::sc_signal<bool> obs_setup_valid, obs_write_valid;
  sc_core::sc_signal<uint32_t> obs_setup_bits, obs_setup_g, obs_write_addr, obs_write_flags;
  sc_core::sc_signal<uint64_t> obs_setup_box, obs_setup_lines, obs_write_tu, obs_write_tv,
      obs_write_su, obs_write_sv;

  const std::vector<Job>& jobs_;
  Scoreboard& scoreboard_;
  size_t next_job_ = 0, last_job_ = SIZE_MAX, current_ = 0, failed_index_ = 0;
  size_t triangles_done_ = 0;
  bool presenting_ = false, in_flight_ = false, checking_ = true, failed_ = false;
  bool replay_ = false, hung_ = false;
  int reset_cycles_ = 3;
  int64_t stalls_ = 0, clock_cycles_ = 0, busy_cycles_ = 0, cycle_limit_ = 0;
  std::mt19937_64 stall_rng_{0};
  std::uniform_real_distribution<double> stall_dist_{0.0, 1.0};

 public:
  void set_job_count(size_t n) { last_job_ = n; }
};

template <class Dut>
int run_bench(const std::vector<Job>& jobs, const Widths& widths) {
  Verilated::traceEverOn(true);
  Scoreboard scoreboard(widths, options.seed);
  Bench<Dut> bench("bench", jobs, scoreboard);
  bench.set_job_count(jobs.size());
  sc_core::sc_start(sc_core::SC_ZERO_TIME);
  auto trace = std::make_unique<VerilatedFstSc>();
  bench.dut.trace(trace.get(), 99);
  if (!options.trace.empty()) trace->open(options.trace.c_str());

  const auto start = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int64_t clock_cycles = bench.clock_cycles();
  const int64_t triangles = static_cast<int64_t>(bench.triangles_done());
  const int64_t mismatches = scoreboard.mismatches() + (bench.hung() ? 1 : 0);

  if (bench.failed() && !bench.hung()) {
    // Re-run the failing triangle with the waveform on.
    const size_t index = bench.failed_index();
    const std::string path =
        options.trace.empty() ? fmt::format("regress_fail_triangle{}.fst", index) : options.trace;
    if (options.trace.empty()) trace->open(path.c_str());
    bench.replay(index);
    sc_core::sc_start();
    trace->close();
    std::cout << fmt::format("waveform of triangle {} (replayed, same back-pressure): {}\n", index,
                             path);
  } else {
    trace->close();
    if (!options.trace.empty()) std::cout << fmt::format("waveform: {}\n", options.trace);
  }
  std::cout << scoreboard.flag_census() << '\n';
  std::cout << fmt::format("blocks compared: {} setups, {} table writes\n",
                           scoreboard.setups_compared(), scoreboard.writes_compared());
  std::cout << fmt::format(
      "{} triangles, {} fragments compared, {} mismatches, RTL cycles {}, model cycles {}, "
      "{:.0f} cycles/s\n",
      triangles, scoreboard.fragments_compared(), mismatches, scoreboard.rtl_cycles(),
      scoreboard.model_cycles(), seconds > 0 ? double(clock_cycles) / seconds : 0.0);
  std::cout << fmt::format("({} clock cycles simulated in {:.2f} s)\n", clock_cycles, seconds);
  return mismatches == 0 ? 0 : 1;
}

std::vector<const Design*> designs_for(const std::string& name) {
  std::vector<const Design*> out;
  if (name == "mix") {
    for (const Design& d : all_designs())
      if (d.kind == Design::Kind::ConstantDepth) out.push_back(&d);
    return out;
  }
  const Design& d = find_design(name);
  if (d.kind != Design::Kind::ConstantDepth)
    throw std::invalid_argument(fmt::format(
        "design '{}' has no RTL; the RTL implements cd-none, cd-linear, cd-dense2, cd-dense4, "
        "cd-dense2-linear (or 'mix': each in turn)", name));
  out.push_back(&d);
  return out;
}

}  // namespace

CLI::App* add_regress_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "regress", "run the SystemVerilog RTL (Verilator + SystemC) against the model, bit and cycle exact");
  add_scene_options(cmd, options.scene, options.scene_options);  // ignored with --random
  cmd->add_option("--random", options.random, "N seeded random triangles (with SPEC §9 hard cases)");
  cmd->add_option("--seed", options.seed, "seed of the random triangles and of the back-pressure")
      ->capture_default_str();
  cmd->add_option("--backpressure", options.backpressure,
                  "probability that the fragment sink stalls a cycle")
      ->check(CLI::Range(0.0, 0.95))
      ->capture_default_str();
  cmd->add_option("--trace", options.trace, "write an FST waveform of the whole run to this file");
  cmd->add_option("--widths", options.widths, "width configuration: default, narrow or wide")
      ->capture_default_str();
  cmd->add_option("--design", options.design,
                  "cd-none, cd-linear, cd-dense2, cd-dense4, cd-dense2-linear, or mix (each in turn)")
      ->capture_default_str();
  cmd->add_option("--only", options.only, "run only triangle N of the source (to chase a mismatch)");
  return cmd;
}

int run_regress_command() {
  try {
    const Widths widths = widths_of(options.widths);
    const std::vector<const Design*> designs = designs_for(options.design);
    std::cout << fmt::format("regress: seed {}\n", options.seed);
    std::vector<Job> jobs;
    if (options.random > 0) {
      jobs = random_jobs(options.random, options.seed, widths, designs);
      std::cout << fmt::format("source: {} random triangles (seed {})\n", options.random, options.seed);
    } else {
      const PreparedScene scene = prepare(load_scene(options.scene, options.scene_options), widths);
      for (size_t i = 0; i < scene.unit.size(); ++i) {
        Job job;
        job.triangle = scene.unit[i];
        job.design = designs[i % designs.size()];
        job.viewport_width = scene.scene.width;
        job.viewport_height = scene.scene.height;
        job.origin = fmt::format("scene {} triangle {}", scene.scene.name, i);
        jobs.push_back(std::move(job));
      }
      std::cout << fmt::format("source: scene {} ({} triangles, {}x{})\n", scene.scene.name,
                               jobs.size(), scene.scene.width, scene.scene.height);
    }
    if (options.only >= 0) {
      if (static_cast<size_t>(options.only) >= jobs.size())
        throw std::invalid_argument(fmt::format("--only {}: the source has {} triangles", options.only, jobs.size()));
      jobs = {jobs[static_cast<size_t>(options.only)]};
      std::cout << fmt::format("only triangle {}: {}\n", options.only, describe_job(jobs[0]));
    }
    std::cout << fmt::format("widths: {} ({})\n", options.widths, describe(widths));
    std::cout << fmt::format("design: {}, back-pressure {}\n", options.design, options.backpressure);
    std::cout.flush();
    if (options.widths == "default") return run_bench<Vcd_scan_unit_default>(jobs, widths);
    if (options.widths == "narrow") return run_bench<Vcd_scan_unit_narrow>(jobs, widths);
    return run_bench<Vcd_scan_unit_wide>(jobs, widths);
  } catch (const std::exception& e) {
    std::cerr << "cdsim regress: error: " << e.what() << '\n';
    return 2;
  }
}

}  // namespace cdsim::rtl
