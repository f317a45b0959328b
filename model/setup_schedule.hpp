// The setup engine's multiplies (model/setup_terms.def) and their schedule
// onto setup_multipliers shared multipliers: which multiplier forms each
// product and from which setup cycle, and so the cycle at which each stage
// reads its results and the setup engine's cycles per triangle. Derived once,
// here; derived_widths.cpp publishes the stage cycles to the model's timing,
// and rtl_header() the whole schedule to rtl/setup_engine.sv.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "widths.hpp"

namespace cdsim {

struct DerivedWidths;

// One sum of products, read by its stage.
struct SetupResult {
  std::string name;
  int stage = 0;          // 0 .. 4: stages A .. E
  int bits = 0;           // kept modulo 2^bits
  int first_term = 0, term_count = 0;
  int multiplier = -1;    // -1 with setup_multipliers = 0 (each product its own)
};

// One signed product a b of a result, added or subtracted.
struct SetupTerm {
  int result = 0;
  bool negate = false;
  int a_bits = 0, b_bits = 0;   // two's-complement operand widths
  int limbs_a = 1, limbs_b = 1;  // setup_mul_bits-bit pieces of |a| and |b|
  int start = 0;                 // the setup cycle of its first partial product
  int cycles() const { return limbs_a * limbs_b; }
};

struct SetupSchedule {
  std::vector<SetupResult> results;
  std::vector<SetupTerm> terms;
  // The cycle (counted from 0, the first setup cycle) at which each stage
  // reads its results and registers what it forms.
  std::array<int, 5> stage_cycle{};
  int div_done = 0;       // the dividers' results are valid from this cycle
  int setup_cycles = 0;   // stage E's cycle + 1
  int busy_cycles = 0;    // multiplier cycles in use, summed over multipliers
  int operand_a_bits = 0, operand_b_bits = 0, acc_bits = 0;
};

// Needs derived's widths and div_cycles (it does not call derive()).
SetupSchedule setup_schedule(const Widths& widths, const DerivedWidths& derived);

// The schedule as SystemVerilog defines for rtl/setup_engine.sv.
std::string setup_schedule_defines(const SetupSchedule& schedule);

}  // namespace cdsim
