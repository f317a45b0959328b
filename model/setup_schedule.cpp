#include "setup_schedule.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "derived_widths.hpp"

namespace cdsim {

namespace {

int ceil_div_int(int a, int b) { return (a + b - 1) / b; }

// The term table of setup_terms.def, in its order.
void read_terms(const Widths& w, const DerivedWidths& d, SetupSchedule& s) {
  const auto result = [&](const char* name, const char* stage, int bits) {
    s.results.push_back({name, stage[0] - 'A', bits, static_cast<int>(s.terms.size()), 0, -1});
  };
  const auto term = [&](const char* name, bool negate, int a_bits, int b_bits) {
    SetupResult& r = s.results.back();
    if (r.name != name)
      throw std::logic_error(fmt::format("setup_terms.def: a term of {} follows {}", name, r.name));
    ++r.term_count;
    s.terms.push_back({static_cast<int>(s.results.size()) - 1, negate, a_bits, b_bits, 1, 1, 0});
  };
#define CDSIM_SETUP_RESULT(name, stage, bits) result(#name, #stage, bits);
#define CDSIM_SETUP_TERM(name, negate, a_bits, b_bits) term(#name, negate != 0, a_bits, b_bits);
#include "setup_terms.def"
#undef CDSIM_SETUP_RESULT
#undef CDSIM_SETUP_TERM
}

}  // namespace

SetupSchedule setup_schedule(const Widths& w, const DerivedWidths& d) {
  SetupSchedule s;
  read_terms(w, d, s);
  const int multipliers = w.setup_multipliers;
  const int limb = w.setup_mul_bits;
  for (SetupTerm& t : s.terms) {
    if (multipliers > 0) {
      t.limbs_a = ceil_div_int(t.a_bits, limb);
      t.limbs_b = ceil_div_int(t.b_bits, limb);
    }
    s.operand_a_bits = std::max(s.operand_a_bits, t.a_bits);
    s.operand_b_bits = std::max(s.operand_b_bits, t.b_bits);
  }
  for (const SetupResult& r : s.results) s.acc_bits = std::max(s.acc_bits, r.bits);

  // Stages in order; the products of a stage run in the cycles before the one
  // that reads them. Stage D waits for the dividers, which stage C starts.
  int phase_start = 0;
  for (int stage = 0; stage < 5; ++stage) {
    if (stage == 3) phase_start = s.stage_cycle[2] + d.div_cycles;
    std::vector<int> order;
    for (int r = 0; r < static_cast<int>(s.results.size()); ++r)
      if (s.results[r].stage == stage) order.push_back(r);
    const auto cycles = [&](int r) {
      int sum = 0;
      for (int k = 0; k < s.results[r].term_count; ++k) sum += s.terms[s.results[r].first_term + k].cycles();
      return sum;
    };
    // Longest first onto the least loaded multiplier; a result's products run
    // back to back on one multiplier, which accumulates their sum.
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cycles(a) > cycles(b); });
    std::vector<int> load(static_cast<size_t>(std::max(multipliers, 1)), 0);
    for (int r : order) {
      SetupResult& result = s.results[r];
      int offset = 0;
      if (multipliers > 0) {
        result.multiplier = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
        offset = load[static_cast<size_t>(result.multiplier)];
        load[static_cast<size_t>(result.multiplier)] += cycles(r);
        s.busy_cycles += cycles(r);
      }
      for (int k = 0; k < result.term_count; ++k) {
        SetupTerm& t = s.terms[result.first_term + k];
        t.start = phase_start + offset;
        if (multipliers > 0) offset += t.cycles();
      }
    }
    // One multiplier a product: the stage reads its sums in the cycle they
    // are formed, or, with setup_product_register, from a register a cycle on.
    const int product_cycles = multipliers > 0 ? *std::max_element(load.begin(), load.end())
                                               : w.setup_product_register;
    // With setup_line_register stage D takes one cycle more: its kappa
    // extremes are registered a cycle before the stage (setup_stage_d.sv).
    s.stage_cycle[stage] = phase_start + product_cycles + (stage == 3 ? w.setup_line_register : 0);
    if (stage == 2) s.div_done = s.stage_cycle[2] + d.div_cycles;
    phase_start = s.stage_cycle[stage] + 1;
  }
  s.setup_cycles = s.stage_cycle[4] + 1;
  return s;
}

std::string setup_schedule_defines(const SetupSchedule& s) {
  // Packed vectors, entry i in bits [i*W +: W], written as hexadecimal.
  const auto packed = [](const std::vector<int>& values, int width) {
    std::string bits;
    for (auto it = values.rbegin(); it != values.rend(); ++it)
      for (int b = width - 1; b >= 0; --b) bits += ((*it >> b) & 1) ? '1' : '0';
    std::string hex;
    const size_t pad = (4 - bits.size() % 4) % 4;
    bits.insert(0, pad, '0');
    for (size_t i = 0; i < bits.size(); i += 4) hex += "0123456789abcdef"[std::stoi(bits.substr(i, 4), nullptr, 2)];
    return fmt::format("{}'h{}", values.size() * static_cast<size_t>(width), hex);
  };
  const auto upper = [](std::string text) {
    for (char& c : text) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    return text;
  };
  std::vector<int> start, multiplier, limbs_a, limbs_b, a_bits, b_bits, negate, result, first, last, result_bits;
  for (size_t i = 0; i < s.terms.size(); ++i) {
    const SetupTerm& t = s.terms[i];
    const SetupResult& r = s.results[static_cast<size_t>(t.result)];
    start.push_back(t.start);
    multiplier.push_back(std::max(r.multiplier, 0));
    limbs_a.push_back(t.limbs_a);
    limbs_b.push_back(t.limbs_b);
    a_bits.push_back(t.a_bits);
    b_bits.push_back(t.b_bits);
    negate.push_back(t.negate);
    result.push_back(t.result);
    first.push_back(static_cast<int>(i) == r.first_term);
    last.push_back(static_cast<int>(i) == r.first_term + r.term_count - 1);
  }
  std::vector<int> result_first_term;
  for (const SetupResult& r : s.results) {
    result_bits.push_back(r.bits);
    result_first_term.push_back(r.first_term);
  }
  std::string out = "// Setup engine multiplies and their schedule (model/setup_terms.def, setup_schedule.cpp)\n";
  out += fmt::format("`define CD_SETUP_TERM_COUNT {}\n`define CD_SETUP_RESULT_COUNT {}\n", s.terms.size(),
                     s.results.size());
  for (size_t r = 0; r < s.results.size(); ++r)
    out += fmt::format("`define CD_SETUP_{} {}  // result index; its terms from CD_SETUP_TERM_{}\n",
                       upper(s.results[r].name), r, upper(s.results[r].name));
  for (const SetupResult& r : s.results)
    out += fmt::format("`define CD_SETUP_TERM_{} {}\n", upper(r.name), r.first_term);
  int pieces = 1;
  for (const SetupTerm& t : s.terms) pieces = std::max({pieces, t.limbs_a, t.limbs_b});
  int piece_bits = 1;
  while ((1 << piece_bits) < pieces) ++piece_bits;
  out += fmt::format("`define CD_SETUP_PIECE_BITS {}  // index of an operand's L-bit piece\n", piece_bits);
  out += "// Per term t, bits [t*W +: W]\n";
  out += fmt::format("`define CD_SETUP_TERM_START {}\n", packed(start, 16));
  out += fmt::format("`define CD_SETUP_TERM_MULTIPLIER {}\n", packed(multiplier, 8));
  out += fmt::format("`define CD_SETUP_TERM_LIMBS_A {}\n", packed(limbs_a, 8));
  out += fmt::format("`define CD_SETUP_TERM_LIMBS_B {}\n", packed(limbs_b, 8));
  out += fmt::format("`define CD_SETUP_TERM_A_BITS {}\n", packed(a_bits, 8));
  out += fmt::format("`define CD_SETUP_TERM_B_BITS {}\n", packed(b_bits, 8));
  out += fmt::format("`define CD_SETUP_TERM_NEGATE {}\n", packed(negate, 1));
  out += fmt::format("`define CD_SETUP_TERM_RESULT {}\n", packed(result, 8));
  out += fmt::format("`define CD_SETUP_TERM_FIRST {}\n", packed(first, 1));
  out += fmt::format("`define CD_SETUP_TERM_LAST {}\n", packed(last, 1));
  out += "// Per result r, bits [r*8 +: 8]\n";
  out += fmt::format("`define CD_SETUP_RESULT_BITS {}\n", packed(result_bits, 8));
  out += fmt::format("`define CD_SETUP_RESULT_FIRST_TERM {}\n", packed(result_first_term, 8));
  return out;
}

}  // namespace cdsim
