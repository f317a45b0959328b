// The setup engine's multiply schedule (model/setup_schedule.cpp): every
// product runs on one multiplier at a time, inside its stage's window, and
// after the values it reads; the piece-by-piece products that the shared
// multipliers form (rtl/setup_multipliers.sv) equal the exact products.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "derived_widths.hpp"
#include "setup_schedule.hpp"

namespace cdsim {
namespace {

Widths with_multipliers(int multipliers, int mul_bits) {
  Widths w;
  w.setup_multipliers = multipliers;
  w.setup_mul_bits = mul_bits;
  return w;
}

TEST(SetupSchedule, FullyParallelEngineTakesOneCycleAStage) {
  const Widths w;
  const DerivedWidths d = derive(w);
  EXPECT_EQ(d.setup_stage_a, 0);
  EXPECT_EQ(d.setup_stage_b, 1);
  EXPECT_EQ(d.setup_stage_c, 2);
  EXPECT_EQ(d.setup_stage_d, 2 + d.div_cycles);
  EXPECT_EQ(d.setup_stage_e, 3 + d.div_cycles);
  EXPECT_EQ(d.setup_cycles, 4 + d.div_cycles);
}

// With the products' register each stage reads its sums a cycle after its
// products: two cycles a stage, and the dividers still start at stage C.
TEST(SetupSchedule, ProductRegisterAddsACycleToEveryStage) {
  Widths w;
  w.setup_product_register = 1;
  const DerivedWidths d = derive(w);
  const SetupSchedule s = setup_schedule(w, d);
  EXPECT_EQ(d.setup_stage_a, 1);
  EXPECT_EQ(d.setup_stage_b, 3);
  EXPECT_EQ(d.setup_stage_c, 5);
  EXPECT_EQ(d.setup_div_done, 5 + d.div_cycles);
  EXPECT_EQ(d.setup_stage_d, 6 + d.div_cycles);
  EXPECT_EQ(d.setup_stage_e, 8 + d.div_cycles);
  EXPECT_EQ(d.setup_cycles, 9 + d.div_cycles);
  // Every term runs in the cycle before its stage reads it.
  for (const SetupTerm& t : s.terms)
    EXPECT_EQ(t.start + 1, s.stage_cycle[static_cast<size_t>(s.results[static_cast<size_t>(t.result)].stage)]);
  w.setup_multipliers = 2;
  EXPECT_THROW(validate(w), std::invalid_argument);
}

// setup_line_register: stage D a cycle later, the others as before it.
TEST(SetupSchedule, LineRegisterAddsACycleToStageD) {
  for (int multipliers : {0, 2}) {
    Widths w = with_multipliers(multipliers, 32);
    const DerivedWidths before = derive(w);
    w.setup_line_register = 1;
    const DerivedWidths after = derive(w);
    EXPECT_EQ(after.setup_stage_c, before.setup_stage_c);
    EXPECT_EQ(after.setup_div_done, before.setup_div_done);
    EXPECT_EQ(after.setup_stage_d, before.setup_stage_d + 1);
    EXPECT_EQ(after.setup_stage_e, before.setup_stage_e + 1);
    EXPECT_EQ(after.setup_cycles, before.setup_cycles + 1);
  }
}

// Stage windows as rtl/setup_engine.sv forms its operands.
std::pair<int, int> window(const SetupSchedule& s, int stage) {
  if (stage == 0) return {0, s.stage_cycle[0]};
  if (stage == 3) return {s.div_done, s.stage_cycle[3]};
  return {s.stage_cycle[static_cast<size_t>(stage - 1)] + 1, s.stage_cycle[static_cast<size_t>(stage)]};
}

TEST(SetupSchedule, EveryProductRunsAloneOnItsMultiplierInsideItsStage) {
  for (int multipliers : {1, 2, 3, 4, 16}) {
    for (int mul_bits : {8, 17, 24, 32}) {
      SCOPED_TRACE(::testing::Message() << "M " << multipliers << " L " << mul_bits);
      const Widths w = with_multipliers(multipliers, mul_bits);
      const DerivedWidths d = derive(w);
      const SetupSchedule s = setup_schedule(w, d);
      std::set<std::pair<int, int>> busy;  // (multiplier, cycle)
      int pieces = 0;
      for (const SetupTerm& t : s.terms) {
        const SetupResult& r = s.results[static_cast<size_t>(t.result)];
        ASSERT_GE(r.multiplier, 0);
        ASSERT_LT(r.multiplier, multipliers);
        // Pieces of L bits cover each operand's magnitude.
        EXPECT_GE(t.limbs_a * mul_bits, t.a_bits);
        EXPECT_GE(t.limbs_b * mul_bits, t.b_bits);
        const auto [first, last] = window(s, r.stage);
        EXPECT_GE(t.start, first);
        EXPECT_LT(t.start + t.cycles() - 1, s.stage_cycle[static_cast<size_t>(r.stage)]);
        EXPECT_LE(t.start + t.cycles() - 1, last);
        for (int c = t.start; c < t.start + t.cycles(); ++c)
          EXPECT_TRUE(busy.insert({r.multiplier, c}).second) << "two products at cycle " << c;
        pieces += t.cycles();
      }
      EXPECT_EQ(pieces, s.busy_cycles);
      // A result's products follow one another on its multiplier.
      for (const SetupResult& r : s.results)
        for (int k = 1; k < r.term_count; ++k) {
          const SetupTerm& before = s.terms[static_cast<size_t>(r.first_term + k - 1)];
          EXPECT_EQ(s.terms[static_cast<size_t>(r.first_term + k)].start, before.start + before.cycles());
        }
      EXPECT_EQ(d.setup_cycles, s.stage_cycle[4] + 1);
      EXPECT_EQ(s.div_done, s.stage_cycle[2] + d.div_cycles);
      // The busiest multiplier of a stage leaves no gap.
      EXPECT_LE(d.setup_cycles, s.busy_cycles + 5 + d.div_cycles);
    }
  }
}

TEST(SetupSchedule, MoreMultipliersNeverTakeLonger) {
  for (int mul_bits : {8, 16, 32}) {
    int previous = 1 << 30;
    for (int multipliers = 1; multipliers <= 16; ++multipliers) {
      const int cycles = derive(with_multipliers(multipliers, mul_bits)).setup_cycles;
      EXPECT_LE(cycles, previous) << "M " << multipliers << " L " << mul_bits;
      EXPECT_GE(cycles, derive(Widths{}).setup_cycles);
      previous = cycles;
    }
  }
}

// The shared multiplier's arithmetic, written from its description in
// rtl/setup_multipliers.sv: |a| and |b| cut into L-bit pieces, each pair's
// product shifted into place and added or subtracted by the product's sign.
__extension__ typedef __int128 Wide;
Wide pieces_product(Wide a, Wide b, int a_bits, int b_bits, int mul_bits) {
  const bool negative = (a < 0) != (b < 0);
  const Wide magnitude_a = a < 0 ? -a : a, magnitude_b = b < 0 ? -b : b;
  const Wide mask = (Wide{1} << mul_bits) - 1;
  Wide sum = 0;
  for (int i = 0; i * mul_bits < a_bits; ++i)
    for (int j = 0; j * mul_bits < b_bits; ++j) {
      const Wide piece = ((magnitude_a >> (i * mul_bits)) & mask) * ((magnitude_b >> (j * mul_bits)) & mask);
      sum += negative ? -(piece << ((i + j) * mul_bits)) : piece << ((i + j) * mul_bits);
    }
  return sum;
}

TEST(SetupSchedule, PiecewiseProductsAreExact) {
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 20000; ++trial) {
    const int a_bits = 2 + static_cast<int>(rng() % 62), b_bits = 2 + static_cast<int>(rng() % 50);
    const int mul_bits = 8 + static_cast<int>(rng() % 25);
    const auto draw = [&](int bits) {
      // Mostly random, sometimes the extremes of the signed range.
      const Wide lo = -(Wide{1} << (bits - 1)), hi = (Wide{1} << (bits - 1)) - 1;
      switch (rng() % 8) {
        case 0: return lo;
        case 1: return hi;
        default: return lo + static_cast<Wide>(rng() % static_cast<uint64_t>(hi - lo + 1 > 0 ? hi - lo + 1 : 1));
      }
    };
    const Wide a = draw(a_bits), b = draw(b_bits);
    ASSERT_TRUE(pieces_product(a, b, a_bits, b_bits, mul_bits) == a * b)
        << "a_bits " << a_bits << " b_bits " << b_bits << " L " << mul_bits;
  }
}

}  // namespace
}  // namespace cdsim
