// What the standalone RTL unit testbenches share: the command line (seed,
// waveform directory, one configuration), a clock that steps a Verilated
// model with an optional VCD, and bit helpers. Each configuration of a unit is
// its own Verilated class (a PREFIX of one CMake target), so the checks are
// templates over the model class.
#pragma once

#include <cinttypes>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>

#include <verilated.h>
#include <verilated_vcd_c.h>

namespace rtl_units {

__extension__ typedef unsigned __int128 u128;

struct Options {
  uint64_t seed = 1;
  std::string vcd_dir;  // empty: no waveform
  std::string only;     // empty: every configuration
};

inline void usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s [--seed N] [--vcd DIR] [--only CONFIG]\n"
               "  --seed N       random operands from seed N (default 1)\n"
               "  --vcd DIR      write DIR/CONFIG.vcd for every configuration run\n"
               "  --only CONFIG  run one configuration (its name as printed)\n",
               program);
}

inline Options parse_options(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--seed" || arg == "--vcd" || arg == "--only") && i + 1 < argc) {
      const std::string value = argv[++i];
      if (arg == "--seed") {
        char* end = nullptr;
        options.seed = std::strtoull(value.c_str(), &end, 0);
        if (value.empty() || *end != '\0') {
          std::fprintf(stderr, "--seed: '%s' is not a number\n", value.c_str());
          std::exit(2);
        }
      } else if (arg == "--vcd") {
        options.vcd_dir = value;
      } else {
        options.only = value;
      }
    } else {
      usage(argv[0]);
      std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
    }
  }
  return options;
}

inline uint64_t mask(int bits) { return bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1; }

inline std::string hex(u128 x) {
  char buffer[40];
  const uint64_t high = static_cast<uint64_t>(x >> 64), low = static_cast<uint64_t>(x);
  if (high != 0) {
    std::snprintf(buffer, sizeof buffer, "0x%" PRIx64 "%016" PRIx64, high, low);
  } else {
    std::snprintf(buffer, sizeof buffer, "0x%" PRIx64, low);
  }
  return buffer;
}

// A model with its own context, clock and optional waveform. Inputs change
// while the clock is low; outputs are read before the rising edge, so a value
// read in cycle c was registered by the edge that ended cycle c-1.
template <class Dut>
class Bench {
 public:
  Bench(const Options& options, const std::string& config) : context_(new VerilatedContext) {
    if (!options.vcd_dir.empty()) context_->traceEverOn(true);
    dut_.reset(new Dut{context_.get(), "dut"});
    if (!options.vcd_dir.empty()) {
      Verilated::mkdir(options.vcd_dir.c_str());
      trace_.reset(new VerilatedVcdC);
      dut_->trace(trace_.get(), 99);
      trace_->open((options.vcd_dir + "/" + config + ".vcd").c_str());
    }
    dut_->clk_i = 0;
    dut_->rst_ni = 1;
    dut_->eval();
  }
  ~Bench() {
    dut_->final();
    if (trace_) trace_->close();
  }
  Bench(const Bench&) = delete;
  Bench& operator=(const Bench&) = delete;

  Dut& dut() { return *dut_; }
  uint64_t cycle() const { return cycle_; }

  // Settle the inputs of the current cycle (clock low).
  void settle() { dut_->eval(); }

  // The rising edge that ends the current cycle, then the falling one. The
  // waveform shows each cycle's settled inputs at time 2 cycle, the edge at
  // 2 cycle + 1.
  void tick() {
    settle();
    dump();
    context_->timeInc(1);
    dut_->clk_i = 1;
    dut_->eval();
    dump();
    context_->timeInc(1);
    dut_->clk_i = 0;
    dut_->eval();
    ++cycle_;
  }

 private:
  void dump() {
    if (trace_) trace_->dump(context_->time());
  }

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Dut> dut_;
  std::unique_ptr<VerilatedVcdC> trace_;
  uint64_t cycle_ = 0;
};

__attribute__((format(printf, 1, 2))) inline std::string format(const char* pattern, ...) {
  char buffer[512];
  va_list args;
  va_start(args, pattern);
  std::vsnprintf(buffer, sizeof buffer, pattern, args);
  va_end(args);
  return buffer;
}

// Set an input port of whatever width Verilator gave it.
template <class Port>
void drive(Port& port, uint64_t value) {
  port = static_cast<Port>(value);
}

// Mismatches are reported up to a limit, each with what it takes to see it again.
class Failures {
 public:
  Failures(const std::string& config, uint64_t seed) : config_(config), seed_(seed) {}
  void report(const std::string& message) {
    if (count_++ < kReported) {
      std::printf("FAIL %s seed %" PRIu64 ": %s\n", config_.c_str(), seed_, message.c_str());
    }
  }
  uint64_t count() const { return count_; }
  void summary() const {
    if (count_ > kReported) std::printf("FAIL %s: %" PRIu64 " mismatches in all\n", config_.c_str(), count_);
    if (count_ > 0) {
      std::printf("  again, with a waveform: --seed %" PRIu64 " --only %s --vcd DIR\n", seed_,
                  config_.c_str());
    }
  }

 private:
  static constexpr uint64_t kReported = 10;
  std::string config_;
  uint64_t seed_;
  uint64_t count_ = 0;
};

}  // namespace rtl_units
