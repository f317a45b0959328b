// The SystemC bench of the Verilated scan unit: a source that feeds triangles
// through the ready/valid input, a sink with random back-pressure, and the
// scoreboard seam (scoreboard.hpp) between them and the C++ model. Inputs are
// driven on the falling clock edge; transfers are sampled on the rising edge,
// where every value read is the settled value of the cycle ending (a valid
// and ready both high there is a transfer, whatever the unit's combinational
// paths from input to output). The source offers the next triangle as soon as
// the last one is taken, so triangles overlap in the unit as it allows.
//
// A header so that each Verilated model instantiates the same bench: the
// built-in width configurations in regress.cpp, and the RTL that
// `cdsim regress --set` verilates into its cache (bench_entry.cpp).
#pragma once

#include <fmt/format.h>
#include <systemc.h>
#include <verilated.h>
#include <verilated_cov.h>
#include <verilated_fst_c.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "cache_files.hpp"
#include "encodings.hpp"
#include "scoreboard.hpp"

namespace cdsim::rtl {

// What a run compared, for `regress --json` and `cdsim merge`.
struct BenchSummary {
  int64_t triangles = 0, fragments = 0, mismatches = 0, hangs = 0;
  int64_t rtl_cycles = 0, model_cycles = 0, setups = 0, table_writes = 0, y_major = 0;
  std::vector<std::pair<std::string, int64_t>> flags;  // triangles with each flag
  std::vector<uint64_t> failed;  // numbers of the triangles that failed
  int64_t clock_cycles = 0;
  // Every clock from the first triangle accepted to the last record delivered,
  // as the bench counted them, and as the model predicts them: its schedule's
  // clocks plus the stalls of back-pressure.
  int64_t clocks = 0, model_clocks = 0;
  double seconds = 0;
};

struct BenchOptions {
  uint64_t seed = 1;          // of the back-pressure (and named in every report)
  // Probability that the fragment sink refuses a fragment offered in a cycle.
  // Each triangle draws from its own generator, seeded by its number, in the
  // cycles its fragments are offered: a replay sees the same refusals.
  double backpressure = 0.0;
  std::string trace;          // FST waveform of the whole run, if not empty
  std::string trace_name;     // the name it is given when the run ends (regress renames it)
  std::string coverage;       // Verilator coverage data of the run, if not empty (a coverage build)
  // Per job: cycles without its record (counted from the last record) before a hang is reported
  // (regress.cpp, hang_cycle_limit: scaled by the model's cycles and the back-pressure).
  std::vector<int64_t> cycle_limits;
  bool unit_has_table = true;       // the unit's HasTable (Scoreboard::set_unit_has_table)
  BenchSummary* summary = nullptr;  // filled at the end, if given
  // Called after each triangle's record with the triangles done (regress's
  // progress on stderr); not during the replay of a failing triangle.
  std::function<void(size_t)> on_record;
};


inline uint64_t mix_seed(uint64_t seed, uint64_t index) {
  uint64_t z = seed + 0x9e3779b97f4a7c15ull * (index + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// The bench as one SystemC thread that owns the Verilated model (Verilator's
// C++ model, not its SystemC wrapper) and calls its eval itself: each clock is
// a falling edge (inputs driven, eval), the sampling of the cycle's transfers,
// then a rising edge (eval). No port crosses an sc_signal, so the kernel does
// no per-cycle work: the thread yields to it every kYieldCycles clocks, which
// is when simulated time advances and the interrupt watch can pause the run.
// docs/rtl.md "The bench" has the profile before and after.
template <class Dut>
class Bench : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Bench);

  static constexpr int64_t kPeriodNs = 10;
  static constexpr int64_t kYieldCycles = 1000;

  Bench(sc_core::sc_module_name name, const std::vector<Job>& jobs, Scoreboard& scoreboard,
        const BenchOptions& options)
      : sc_module(name), dut("dut"), jobs_(jobs), scoreboard_(scoreboard), options_(options) {
    // Trace time in the model's time precision (10^prec s a tick).
    ticks_per_ns_ = 1;
    for (int p = dut.contextp()->timeprecision(); p < -9; ++p) ticks_per_ns_ *= 10;
    SC_THREAD(run);
  }

  // The waveform the clocks are dumped into while it is open.
  void set_trace(VerilatedFstC* trace) { trace_ = trace; }

  // Replays one triangle alone from an idle unit (after a mismatch, with the
  // waveform on): the same values and back-pressure; its cycles are those of a
  // triangle with nothing before it.
  void replay(size_t index) {
    replay_ = true;
    next_job_ = index;
    last_job_ = index + 1;
    failed_ = false;
    stopping_ = false;
    checking_ = true;
    scoreboard_.restart();
    done_ = false;  // the thread waits for this in simulated time
  }

  bool failed() const { return failed_; }
  size_t failed_index() const { return failed_index_; }
  bool hung() const { return hung_; }
  int64_t clock_cycles() const { return clock_cycles_; }
  // From the clock that accepted the first triangle to the one that delivered
  // the last record, both included.
  int64_t busy_span() const { return last_record_clock_ < 0 ? 0 : last_record_clock_ - first_accept_clock_ + 1; }
  int64_t total_stalls() const { return total_stalls_; }
  size_t triangles_done() const { return triangles_done_; }

  Dut dut;

 private:
  // Runs clocks until the source is done and the unit empty (or a hang), then
  // pauses the kernel: sc_start returns to run_bench. A replay resumes it.
  void run() {
    dut.clk_i = 1;  // as the clock starts: high, the first edge a falling one
    dut.eval();
    dump();
    for (;;) {
      int64_t since_yield = 0;
      while (!done_) {
        falling_edge();
        dut.clk_i = 0;
        dut.eval();
        time_ += kPeriodNs / 2;
        dump();
        if (done_) break;  // a hang
        rising_edge();
        dut.clk_i = 1;
        dut.eval();
        time_ += kPeriodNs / 2;
        dump();
        if (++since_yield == kYieldCycles) {
          since_yield = 0;
          wait(sc_core::sc_time(double(kYieldCycles * kPeriodNs), sc_core::SC_NS));
        }
      }
      sc_core::sc_pause();
      while (done_) wait(sc_core::sc_time(double(kYieldCycles * kPeriodNs), sc_core::SC_NS));
    }
  }

  void dump() {
    if (trace_ && trace_->isOpen()) trace_->dump(static_cast<uint64_t>(time_ * ticks_per_ns_));
  }

  // An input port takes the low `bits` bits of the value (Verilator's C++
  // model assumes the bits above a port's width are zero).
  template <class Port>
  static void drive(Port& port, uint64_t value, int bits) {
    port = static_cast<Port>(bits >= 64 ? value : value & ((uint64_t{1} << bits) - 1));
  }

  // Drives the inputs for the coming cycle.
  void falling_edge() {
    ++clock_cycles_;
    if (reset_cycles_ > 0) {
      dut.rst_ni = 0;
      dut.rec_ready_i = 1;
      if (--reset_cycles_ == 0) dut.rst_ni = 1;
      return;
    }
    if (!in_flight_.empty() && ++busy_cycles_ > cycle_limit_) {
      const Job& job = jobs_[in_flight_.front()];
      std::cout << fmt::format("HANG seed {} triangle {}: no record after {} cycles\n  triangle {}\n",
                               options_.seed, job.number, busy_cycles_, describe_job(job));
      hung_ = true;
      done_ = true;
      return;
    }
    // Sink: the fragment offered this cycle (frag_valid depends on the unit's
    // state only) is refused with the probability of back-pressure.
    bool ready = true;
    if (dut.frag_valid_o && options_.backpressure > 0)
      ready = !(stall_dist_(stall_rng_) < options_.backpressure);
    dut.frag_ready_i = ready;
    // Source: the next triangle, offered until taken.
    if (!presenting_ && !stopping_ && next_job_ < last_job_) {
      const Job& job = jobs_[next_job_];
      const auto& v = job.triangle.vertex;
      drive(dut.tri_x0_i, static_cast<uint32_t>(v[0].x), 32);
      drive(dut.tri_y0_i, static_cast<uint32_t>(v[0].y), 32);
      drive(dut.tri_q0_i, v[0].q_float, 32);
      drive(dut.tri_u0_i, static_cast<uint32_t>(v[0].u), 32);
      drive(dut.tri_v0_i, static_cast<uint32_t>(v[0].v), 32);
      drive(dut.tri_x1_i, static_cast<uint32_t>(v[1].x), 32);
      drive(dut.tri_y1_i, static_cast<uint32_t>(v[1].y), 32);
      drive(dut.tri_q1_i, v[1].q_float, 32);
      drive(dut.tri_u1_i, static_cast<uint32_t>(v[1].u), 32);
      drive(dut.tri_v1_i, static_cast<uint32_t>(v[1].v), 32);
      drive(dut.tri_x2_i, static_cast<uint32_t>(v[2].x), 32);
      drive(dut.tri_y2_i, static_cast<uint32_t>(v[2].y), 32);
      drive(dut.tri_q2_i, v[2].q_float, 32);
      drive(dut.tri_u2_i, static_cast<uint32_t>(v[2].u), 32);
      drive(dut.tri_v2_i, static_cast<uint32_t>(v[2].v), 32);
      drive(dut.viewport_width_i, static_cast<uint32_t>(job.viewport_width), 16);
      drive(dut.viewport_height_i, static_cast<uint32_t>(job.viewport_height), 16);
      const DesignSelect select = design_select(*job.design);
      drive(dut.kind_i, static_cast<uint32_t>(select.kind), 2);
      drive(dut.segment_log2_i, static_cast<uint32_t>(select.segment_log2), 3);
      drive(dut.density_log2_i, static_cast<uint32_t>(select.density_log2), 2);
      drive(dut.correction_i, select.correction, 1);
      drive(dut.persp_i, select.persp, 1);
      drive(dut.quadratic_i, select.quadratic, 1);
      drive(dut.fallback_i, select.fallback, 1);
      drive(dut.kim_pipelined_i, select.kim_pipelined, 1);
      presenting_ = true;
      presented_ = next_job_++;
    }
    if (stopping_) presenting_ = false;  // a failure: offer nothing more
    dut.tri_valid_i = presenting_;
  }

  // Samples the transfers of the cycle ending: the outputs as the inputs of
  // the falling edge left them settled, before the rising edge's eval.
  void rising_edge() {
    if (reset_cycles_ > 0 || hung_) return;
    if (dut.frag_valid_o) {
      if (!dut.frag_ready_i) {
        ++stalls_;
      } else if (checking_) {
        RtlFragment f;
        f.x = static_cast<int64_t>(dut.frag_x_o);
        f.y = static_cast<int64_t>(dut.frag_y_o);
        f.u = static_cast<int64_t>(dut.frag_u_o);
        f.v = static_cast<int64_t>(dut.frag_v_o);
        f.flags = dut.frag_flags_o;
        if (!scoreboard_.fragment(f)) fail();
      }
    }
    if (checking_ && dut.obs_setup_valid_o) {
      const uint32_t bits = dut.obs_setup_bits_o;
      const uint64_t box = dut.obs_setup_box_o, lines = dut.obs_setup_lines_o;
      RtlSetup a;
      const auto bit = [&](int position) { return ((bits >> position) & 1) != 0; };
      const auto field = [](uint64_t word, int lsb, int width) {
        return static_cast<uint32_t>((word >> lsb) & ((uint64_t{1} << width) - 1));
      };
      a.empty = bit(encoding::OBS_SETUP_EMPTY);
      a.x_major = bit(encoding::OBS_SETUP_X_MAJOR);
      a.no_lines = bit(encoding::OBS_SETUP_NO_LINES);
      a.depth_range = bit(encoding::OBS_SETUP_DEPTH_RANGE);
      a.g = static_cast<int32_t>(dut.obs_setup_g_o);
      a.major_lo = field(box, encoding::OBS_BOX_MAJOR_LO, 16);
      a.major_count = field(box, encoding::OBS_BOX_MAJOR_COUNT, 16);
      a.minor_lo = field(box, encoding::OBS_BOX_MINOR_LO, 16);
      a.minor_hi = field(box, encoding::OBS_BOX_MINOR_HI, 16);
      a.pixel_line_lo = static_cast<int32_t>(field(lines, encoding::OBS_LINES_LO, 32));
      a.pixel_line_hi = static_cast<int32_t>(field(lines, encoding::OBS_LINES_HI, 32));
      if (!scoreboard_.setup(a)) fail();
    }
    if (checking_ && dut.obs_write_valid_o) {
      RtlTableWrite w;
      w.address = dut.obs_write_addr_o;
      w.t_u = static_cast<int64_t>(dut.obs_write_tu_o);
      w.t_v = static_cast<int64_t>(dut.obs_write_tv_o);
      w.s_u = static_cast<int64_t>(dut.obs_write_su_o);
      w.s_v = static_cast<int64_t>(dut.obs_write_sv_o);
      const uint32_t flags = dut.obs_write_flags_o;
      w.saturated = (flags >> encoding::OBS_WRITE_SATURATED) & 1;
      w.depth_range = (flags >> encoding::OBS_WRITE_DEPTH_RANGE) & 1;
      w.eps_saturated = (flags >> encoding::OBS_WRITE_EPS_SATURATED) & 1;
      w.eps = static_cast<int64_t>(dut.obs_write_eps_o);
      if (!scoreboard_.table_write(w)) fail();
    }
    if (dut.rec_valid_o && dut.rec_ready_i) {
      RtlRecord r;
      r.cycles = static_cast<int64_t>(dut.rec_cycles_o);
      r.lines = dut.rec_lines_o;
      r.bands = dut.rec_bands_o;
      r.pixels = dut.rec_pixels_o;
      r.flags = dut.rec_flags_o;
      if (checking_ && !scoreboard_.record(r, stalls_)) fail();
      if (!replay_) {
        last_record_clock_ = clock_cycles_;
        total_stalls_ += stalls_;
      }
      stalls_ = 0;
      busy_cycles_ = 0;
      if (!in_flight_.empty()) in_flight_.pop_front();
      ++triangles_done_;
      if (options_.on_record && !replay_) options_.on_record(triangles_done_);
      if (!in_flight_.empty()) start_triangle(in_flight_.front());
    }
    if (dut.tri_valid_i && dut.tri_ready_o && presenting_) {
      const size_t job = presented_;
      presenting_ = false;
      if (first_accept_clock_ < 0 && !replay_) first_accept_clock_ = clock_cycles_;
      in_flight_.push_back(job);
      if (checking_) scoreboard_.accept(job, jobs_[job]);
      if (in_flight_.size() == 1) {
        busy_cycles_ = 0;
        start_triangle(job);
      }
    }
    const bool source_done = stopping_ || (next_job_ >= last_job_ && !presenting_);
    if (source_done && in_flight_.empty()) done_ = true;
  }

  // The triangle whose fragments come next: its back-pressure generator, and
  // the cycles it may take until its record.
  void start_triangle(size_t job) {
    cycle_limit_ = options_.cycle_limits.at(job);
    stall_rng_.seed(mix_seed(options_.seed, jobs_[job].number));
  }

  void fail() {
    if (!failed_) {
      failed_ = true;
      failed_index_ = scoreboard_.failed_index();
      std::cout << scoreboard_.mismatch() << '\n';
    }
    // Drain the triangles in the unit without further checks, offer no more.
    checking_ = replay_;
    stopping_ = true;
  }

  const std::vector<Job>& jobs_;
  Scoreboard& scoreboard_;
  const BenchOptions& options_;
  size_t next_job_ = 0, last_job_ = SIZE_MAX, presented_ = 0, failed_index_ = 0;
  size_t triangles_done_ = 0;
  std::deque<size_t> in_flight_;  // accepted, not yet recorded, oldest first
  bool presenting_ = false, checking_ = true, failed_ = false, stopping_ = false;
  bool replay_ = false, hung_ = false, done_ = false;
  VerilatedFstC* trace_ = nullptr;
  int64_t time_ = 0, ticks_per_ns_ = 1;  // simulated ns, for the waveform
  int reset_cycles_ = 3;
  int64_t stalls_ = 0, clock_cycles_ = 0, busy_cycles_ = 0, cycle_limit_ = 0;
  int64_t first_accept_clock_ = -1, last_record_clock_ = -1, total_stalls_ = 0;
  std::mt19937_64 stall_rng_{0};
  std::uniform_real_distribution<double> stall_dist_{0.0, 1.0};

 public:
  void set_job_count(size_t n) { last_job_ = n; }
};

template <class Dut>
int run_bench(const std::vector<Job>& jobs, const Widths& widths, const BenchOptions& options) {
  Verilated::traceEverOn(true);
  Scoreboard scoreboard(widths, options.seed);
  scoreboard.set_unit_has_table(options.unit_has_table);
  Bench<Dut> bench("bench", jobs, scoreboard, options);
  bench.set_job_count(jobs.size());
  auto trace = std::make_unique<VerilatedFstC>();
  bench.dut.trace(trace.get(), 99);
  bench.set_trace(trace.get());
  if (!options.trace.empty()) trace->open(options.trace.c_str());

  const auto start = std::chrono::steady_clock::now();
  sc_core::sc_start();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int64_t clock_cycles = bench.clock_cycles();
  const int64_t triangles = static_cast<int64_t>(bench.triangles_done());
  // Every clock counted: from the first accept to the last record, the unit
  // spends exactly the model's clocks plus the stalls (when every triangle
  // matched; a failing one is drained unchecked).
  const int64_t clocks = bench.busy_span();
  const int64_t model_clocks = scoreboard.model_cycles() + bench.total_stalls();
  const bool clocks_differ = !bench.failed() && !bench.hung() && clocks != model_clocks;
  if (clocks_differ)
    std::cout << fmt::format(
        "MISMATCH clocks (seed {}): {} clocks from the first triangle accepted to the last record "
        "delivered; the model's schedule plus {} stalls gives {}\n",
        options.seed, clocks, bench.total_stalls(), model_clocks);
  const int64_t mismatches = scoreboard.mismatches() + (bench.hung() ? 1 : 0) + (clocks_differ ? 1 : 0);

  if (bench.failed() && !bench.hung()) {
    // Re-run the failing triangle with the waveform on.
    const size_t index = bench.failed_index();
    const std::string path =
        options.trace.empty() ? fmt::format("regress_fail_triangle{}.fst", index) : options.trace_name;
    // Without --trace too, the waveform goes beside its name and is renamed
    // over it, as every output is: never half a file, never over a device.
    const std::string temporary = options.trace.empty() ? temporary_beside(path).string() : std::string();
    if (options.trace.empty()) trace->open(temporary.c_str());
    bench.replay(index);
    sc_core::sc_start();
    trace->close();
    std::string written = path;
    if (options.trace.empty()) {
      try {
        check_regular_output("the waveform", path);
        publish_file(temporary, path);
      } catch (const std::exception& e) {
        written = fmt::format("{} ({})", temporary, e.what());
      }
    }
    std::cout << fmt::format("waveform of triangle {} (replayed, same back-pressure): {}\n", index,
                             written);
  } else {
    trace->close();
    if (!options.trace.empty()) std::cout << fmt::format("waveform: {}\n", options.trace_name);
  }
  bench.dut.final();
  if (!options.coverage.empty()) Verilated::threadContextp()->coveragep()->write(options.coverage.c_str());
  std::cout << scoreboard.flag_census() << '\n';
  std::cout << fmt::format("blocks compared: {} setups, {} table writes\n",
                           scoreboard.setups_compared(), scoreboard.writes_compared());
  std::cout << fmt::format(
      "{} triangles, {} fragments compared, {} mismatches, RTL cycles {}, model cycles {}, "
      "{:.0f} cycles/s\n",
      triangles, scoreboard.fragments_compared(), mismatches, scoreboard.rtl_cycles(),
      scoreboard.model_cycles(), seconds > 0 ? double(clock_cycles) / seconds : 0.0);
  std::cout << fmt::format("clocks from the first accept to the last record: {} (model {} + {} stalls)\n",
                           clocks, scoreboard.model_cycles(), bench.total_stalls());
  std::cout << fmt::format("({} clock cycles simulated in {:.2f} s)\n", clock_cycles, seconds);
  if (BenchSummary* s = options.summary) {
    s->triangles = triangles;
    s->fragments = scoreboard.fragments_compared();
    s->mismatches = mismatches;
    s->hangs = bench.hung() ? 1 : 0;
    s->rtl_cycles = scoreboard.rtl_cycles();
    s->model_cycles = scoreboard.model_cycles();
    s->setups = scoreboard.setups_compared();
    s->table_writes = scoreboard.writes_compared();
    s->y_major = scoreboard.y_major();
    s->flags = scoreboard.flag_counts();
    if (bench.failed()) s->failed.push_back(jobs[bench.failed_index()].number);
    s->clock_cycles = clock_cycles;
    s->clocks = clocks;
    s->model_clocks = model_clocks;
    s->seconds = seconds;
  }
  return mismatches == 0 ? 0 : 1;
}

}  // namespace cdsim::rtl
