// Checks the fixed-point layer (model/fixed.hpp) against SystemC's sc_fix / sc_ufix,
// used as an independent oracle.
//
// Mapping (see the header comment of fixed.hpp):
//   Format{int_bits, frac_bits, true}  == sc_fix (wl = int_bits + frac_bits, iwl = int_bits)
//   Format{int_bits, frac_bits, false} == sc_ufix(wl = int_bits + frac_bits, iwl = int_bits)
//   Round::Trunc == SC_TRN, Round::Nearest == SC_RND,
//   Overflow::Saturate == SC_SAT, Overflow::Wrap == SC_WRAP.
//
// A raw model value is the integer held in the sc_fix word: it is read back bit by bit
// (bit 0 = LSB of the word) and, when the word is narrow enough, cross-checked against
// to_double() * 2^frac_bits.
//
// Every random stream is derived from kSeed and the combination under test; both are
// part of the SCOPED_TRACE of each combination, so a failure names everything needed
// to reproduce it.
#define SC_INCLUDE_FX
#include <systemc>

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "fixed.hpp"

// libsystemc defines main() in terms of sc_main(); gtest_main supplies the main() that
// runs, but the shared library still needs the symbol to link.
int sc_main(int, char*[]) { return 0; }

namespace {

using cdsim::fx::Format;
using cdsim::fx::Overflow;
using cdsim::fx::Round;
using cdsim::fx::Wide;
using sc_dt::sc_fix;
using sc_dt::sc_fxnum;
using sc_dt::sc_fxval;
using sc_dt::sc_o_mode;
using sc_dt::sc_q_mode;
using sc_dt::sc_ufix;

constexpr std::uint64_t kSeed = 0xC0D5'1A7E'2024'0001ULL;

// ---------------------------------------------------------------------------------------
// Deterministic random numbers (splitmix64: identical on every standard library).

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi] (the modulo bias is irrelevant here).
  int range(int lo, int hi) {
    return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  bool coin() { return (next() & 1) != 0; }
  // Random two's-complement value of exactly `bits` bits (1..126), sign-extended.
  Wide signed_bits(int bits) {
    const Wide word = (static_cast<Wide>(next()) << 64) | static_cast<Wide>(next());
    const Wide mask = (Wide{1} << bits) - 1;
    Wide v = word & mask;
    if (v >= (Wide{1} << (bits - 1))) v -= Wide{1} << bits;
    return v;
  }

 private:
  std::uint64_t state_;
};

std::uint64_t mix(std::uint64_t seed, std::uint64_t value) {
  Rng r(seed ^ (value * 0x9E3779B97F4A7C15ULL));
  return r.next();
}

// ---------------------------------------------------------------------------------------
// Printing helpers.

std::string str(Wide v) {
  if (v == 0) return "0";
  const bool negative = v < 0;
  // Work on the negative side so that the most negative value needs no special case.
  Wide n = negative ? v : -v;
  std::string digits;
  while (n != 0) {
    digits.insert(digits.begin(), static_cast<char>('0' - static_cast<int>(n % 10)));
    n /= 10;
  }
  return negative ? "-" + digits : digits;
}

std::string hex_double(double d) {
  std::ostringstream os;
  os.precision(17);
  os << d << " (" << std::hexfloat << d << ")";
  return os.str();
}

// ---------------------------------------------------------------------------------------
// Modes and formats.

struct Mode {
  Round round;
  Overflow overflow;
  sc_q_mode q;
  sc_o_mode o;
  const char* name;
};

const Mode kModes[] = {
    {Round::Trunc, Overflow::Saturate, sc_dt::SC_TRN, sc_dt::SC_SAT, "Trunc/Saturate (SC_TRN,SC_SAT)"},
    {Round::Trunc, Overflow::Wrap, sc_dt::SC_TRN, sc_dt::SC_WRAP, "Trunc/Wrap (SC_TRN,SC_WRAP)"},
    {Round::Nearest, Overflow::Saturate, sc_dt::SC_RND, sc_dt::SC_SAT, "Nearest/Saturate (SC_RND,SC_SAT)"},
    {Round::Nearest, Overflow::Wrap, sc_dt::SC_RND, sc_dt::SC_WRAP, "Nearest/Wrap (SC_RND,SC_WRAP)"},
};

// int_bits and frac_bits of t_format / s_format / out_format (widths.def: t_int, s_int,
// out_int in 2..30; t_frac, s_frac, out_frac in 0..28), including the defaults
// 17.12 (T), 17.20 (S) and 16.8 (out).
const int kIntBits[] = {2, 3, 8, 16, 17, 24, 30};
const int kFracBits[] = {0, 1, 8, 12, 16, 20, 24, 28};

std::vector<Format> all_formats() {
  std::vector<Format> formats;
  for (const bool is_signed : {true, false})
    for (const int i : kIntBits)
      for (const int f : kFracBits) formats.push_back(Format{i, f, is_signed});
  // The widest words the layer is specified for (total <= 62).
  formats.push_back(Format{34, 28, true});
  formats.push_back(Format{62, 0, true});
  formats.push_back(Format{2, 60, true});
  formats.push_back(Format{34, 28, false});
  formats.push_back(Format{1, 0, false});  // a single unsigned bit
  return formats;
}

std::string describe(const Format& f) {
  std::ostringstream os;
  os << (f.is_signed ? "signed" : "unsigned") << " int_bits=" << f.int_bits
     << " frac_bits=" << f.frac_bits << " (" << (f.is_signed ? "sc_fix" : "sc_ufix") << "<"
     << f.int_bits + f.frac_bits << "," << f.int_bits << ">)";
  return os.str();
}

std::uint64_t combo_seed(const Format& f, const Mode& m, std::uint64_t salt) {
  std::uint64_t s = mix(kSeed, salt);
  s = mix(s, static_cast<std::uint64_t>(f.int_bits));
  s = mix(s, static_cast<std::uint64_t>(f.frac_bits));
  s = mix(s, f.is_signed ? 1 : 0);
  s = mix(s, static_cast<std::uint64_t>(m.round) * 2 + static_cast<std::uint64_t>(m.overflow));
  return s;
}

// Range of the format's raw integers, computed here independently of Format::max_raw().
Wide expected_max_raw(const Format& f) {
  const int total = f.int_bits + f.frac_bits;
  return (Wide{1} << (f.is_signed ? total - 1 : total)) - 1;
}
Wide expected_min_raw(const Format& f) {
  const int total = f.int_bits + f.frac_bits;
  return f.is_signed ? -(Wide{1} << (total - 1)) : Wide{0};
}

// ---------------------------------------------------------------------------------------
// SystemC side.

// Integer held in the word of x (wl bits), read bit by bit.
Wide read_raw(const sc_fxnum& x, int wl, bool is_signed) {
  Wide r = 0;
  for (int i = wl - 1; i >= 0; --i) r = r * 2 + (static_cast<bool>(x[i]) ? 1 : 0);
  if (is_signed && static_cast<bool>(x[wl - 1])) r -= Wide{1} << wl;
  return r;
}

// Writes raw (two's complement, wl bits) into the word of x bit by bit.
void write_raw(sc_fxnum& x, int wl, Wide raw) {
  for (int i = 0; i < wl; ++i) x[i] = ((raw >> i) & 1) != 0;
}

struct OracleResult {
  Wide raw = 0;
  bool overflow = false;       // sc_fxnum::overflow_flag() after the assignment
  bool outside = false;        // the quantised, unconstrained value lies outside the format
  double as_double = 0.0;      // to_double() of the result
};

// Range of the format as exact sc_fxval bounds.
sc_fxval format_hi(const Format& f) {
  // 2^(int_bits - sign) - 2^-frac_bits
  const int magnitude_int = f.is_signed ? f.int_bits - 1 : f.int_bits;
  return (sc_fxval(1) << magnitude_int) - (sc_fxval(1) >> f.frac_bits);
}
sc_fxval format_lo(const Format& f) {
  return f.is_signed ? -(sc_fxval(1) << (f.int_bits - 1)) : sc_fxval(0);
}

// Casts `value` (an exact sc_fxval, or anything sc_fxnum accepts) into format f with mode
// m. int_bits_hint bounds the magnitude of value (value < 2^int_bits_hint), so that an
// unconstrained twin with enough integer bits can tell whether the quantised value
// overflows.
template <class Value>
OracleResult oracle_cast(const Value& value, const Format& f, const Mode& m, int int_bits_hint) {
  const int wl = f.int_bits + f.frac_bits;
  OracleResult res;
  if (f.is_signed) {
    sc_fix dst(wl, f.int_bits, m.q, m.o);
    dst = value;
    res.raw = read_raw(dst, wl, true);
    res.overflow = dst.overflow_flag();
    res.as_double = dst.to_double();
  } else {
    sc_ufix dst(wl, f.int_bits, m.q, m.o);
    dst = value;
    res.raw = read_raw(dst, wl, false);
    res.overflow = dst.overflow_flag();
    res.as_double = dst.to_double();
  }
  // Same quantisation, but enough integer bits that nothing can overflow.
  const int big_iwl = std::max(int_bits_hint, f.int_bits) + 3;
  sc_fix unconstrained(big_iwl + f.frac_bits, big_iwl, m.q, sc_dt::SC_WRAP);
  unconstrained = value;
  if (unconstrained.overflow_flag()) ADD_FAILURE() << "test bug: unconstrained twin overflowed";
  res.outside = unconstrained > format_hi(f) || unconstrained < format_lo(f);
  return res;
}

// ---------------------------------------------------------------------------------------
// Comparison with failure budget (so that a systematic bug does not print 100000 lines).

class Checker {
 public:
  explicit Checker(int budget = 25) : budget_(budget) {}
  bool exhausted() const { return failures_ >= budget_; }
  long long samples() const { return samples_; }

  // Compares the model against the oracle; `what` describes the input (called on failure).
  template <class Describe>
  void check(Wide model_raw, bool model_flag, const OracleResult& o, const Format& f,
             Describe&& what) {
    ++samples_;
    const bool raw_ok = model_raw == o.raw;
    const bool flag_ok = model_flag == o.overflow && o.overflow == o.outside;
    // The raw read-back must agree with sc_fix's own value (exact when wl <= 53).
    bool readback_ok = true;
    if (f.int_bits + f.frac_bits <= 53)
      readback_ok = std::ldexp(o.as_double, f.frac_bits) == static_cast<double>(o.raw);
    if (raw_ok && flag_ok && readback_ok) return;
    ++failures_;
    ADD_FAILURE() << what() << "\n  model raw      = " << str(model_raw)
                  << "\n  sc_fix raw     = " << str(o.raw)
                  << "\n  model overflow = " << model_flag
                  << "\n  sc_fix overflow_flag = " << o.overflow
                  << ", unconstrained value outside range = " << o.outside
                  << (readback_ok ? "" : "\n  (test bug: bit read-back disagrees with to_double)");
    if (exhausted()) ADD_FAILURE() << "failure budget exhausted; stopping this test";
  }

 private:
  int budget_;
  int failures_ = 0;
  long long samples_ = 0;
};

long long g_narrow_samples = 0;
long long g_double_samples = 0;

// ---------------------------------------------------------------------------------------
// narrow()

// One narrow() case: source = raw * 2^-from_frac, held in an sc_fix<src_wl, src_wl - from_frac>.
void check_narrow_case(Checker& checker, Wide raw, int src_wl, int from_frac, const Format& f,
                       const Mode& m) {
  sc_fix src(src_wl, src_wl - from_frac, sc_dt::SC_TRN, sc_dt::SC_WRAP);
  write_raw(src, src_wl, raw);
  if (read_raw(src, src_wl, true) != raw) {
    ADD_FAILURE() << "test bug: source sc_fix does not hold raw " << str(raw);
    return;
  }
  const OracleResult o = oracle_cast(src, f, m, src_wl - from_frac);

  bool model_flag = false;
  const Wide model_raw = cdsim::fx::narrow(raw, from_frac, f, m.round, m.overflow, &model_flag);
  checker.check(model_raw, model_flag, o, f, [&] {
    std::ostringstream os;
    os << "narrow(raw=" << str(raw) << ", from_frac=" << from_frac << ") into " << describe(f)
       << " mode " << m.name << "; source sc_fix<" << src_wl << "," << src_wl - from_frac
       << ">";
    return os.str();
  });
}

// Random source raw for a given source word: uniform bits, extremes, and exact ties
// (the dropped bits are exactly one half LSB of the target).
Wide random_source(Rng& rng, int src_wl, int from_frac, const Format& f) {
  const int kind = rng.range(0, 9);
  const Wide max = (Wide{1} << (src_wl - 1)) - 1;
  const Wide min = -(Wide{1} << (src_wl - 1));
  if (kind == 0) {
    const Wide special[] = {0, 1, -1, max, min, max - 1, min + 1};
    const Wide v = special[rng.range(0, 6)];
    return v > max ? max : v;  // a 1-bit source holds only 0 and -1
  }
  Wide raw = rng.signed_bits(rng.range(1, src_wl));  // varied magnitudes
  const int shift = from_frac - f.frac_bits;
  if (kind <= 3 && shift >= 1 && shift < src_wl) {
    // Exact tie: bits below the target LSB are 100...0.
    const Wide half = Wide{1} << (shift - 1);
    raw = (raw & ~((Wide{1} << shift) - 1)) | half;
    if (raw > max) raw -= Wide{1} << shift;
  } else if (kind == 4 && shift >= 1 && shift < src_wl) {
    // Just below / above a tie.
    const Wide half = Wide{1} << (shift - 1);
    raw = (raw & ~((Wide{1} << shift) - 1)) | half;
    raw += rng.coin() ? 1 : -1;
    if (raw > max) raw = max;
    if (raw < min) raw = min;
  } else if (kind == 5) {
    // Around the target's range limits, expressed at from_frac.
    const Wide edge = rng.coin() ? expected_max_raw(f) : expected_min_raw(f);
    Wide scaled = 0;
    if (shift >= 0 && shift < 60 && (edge == 0 || cdsim::fx::bit_length(edge) + shift < src_wl))
      scaled = edge * (Wide{1} << shift);
    else if (shift < 0 && -shift < 100)
      scaled = edge >> -shift;
    raw = scaled + rng.range(-3, 3);
    if (raw > max) raw = max;
    if (raw < min) raw = min;
  }
  return raw;
}

TEST(FixedPointOracle, NarrowMatchesScFixOnEveryFormatAndMode) {
  long long combos = 0;
  for (const Format& f : all_formats()) {
    for (const Mode& m : kModes) {
      const std::uint64_t seed = combo_seed(f, m, 1);
      SCOPED_TRACE(::testing::Message() << "kSeed=0x" << std::hex << kSeed << " combo seed=0x"
                                        << seed << std::dec << " target " << describe(f)
                                        << " mode " << m.name);
      Rng rng(seed);
      Checker checker;
      ++combos;
      for (int n = 0; n < 1000 && !checker.exhausted(); ++n) {
        const int src_wl = rng.range(1, 62);
        int from_frac = 0;
        if (rng.range(0, 3) != 0) {
          // Source binary point close to the target's, so values straddle its range.
          from_frac = src_wl - (f.int_bits + rng.range(-8, 8));
        } else {
          from_frac = rng.range(-4, 90);
        }
        const Wide raw = random_source(rng, src_wl, from_frac, f);
        check_narrow_case(checker, raw, src_wl, from_frac, f, m);
      }
      g_narrow_samples += checker.samples();
    }
  }
  RecordProperty("combinations", static_cast<int>(combos));
  std::printf("[ narrow   ] %lld combinations, %lld samples\n", combos, g_narrow_samples);
}

// Sources wider than 64 bits, as the model produces them (a Wide product narrowed to a
// table or output format: Round::Nearest, Overflow::Saturate in setup_engine.cpp,
// divide_datapath.cpp, correction_adder.hpp).
TEST(FixedPointOracle, NarrowFromWideProductsMatchesScFix) {
  long long samples = 0;
  long long combos = 0;
  for (const Format& f : all_formats()) {
    for (const Mode& m : kModes) {
      const std::uint64_t seed = combo_seed(f, m, 2);
      SCOPED_TRACE(::testing::Message() << "kSeed=0x" << std::hex << kSeed << " combo seed=0x"
                                        << seed << std::dec << " target " << describe(f)
                                        << " mode " << m.name);
      Rng rng(seed);
      Checker checker;
      ++combos;
      for (int n = 0; n < 200 && !checker.exhausted(); ++n) {
        const int src_wl = rng.range(63, 120);
        // Binary point at or above the target's, so narrow() shifts right. Wide sources
        // shifted left are covered by NarrowWideSourceLeftShiftSaturates (Saturate) and by
        // NarrowWrapWideSourceLeftShift (Wrap).
        const int from_frac = rng.coin() ? src_wl - (f.int_bits + rng.range(-8, 8))
                                         : rng.range(f.frac_bits, 110);
        if (from_frac < f.frac_bits) continue;
        const Wide raw = random_source(rng, src_wl, from_frac, f);
        check_narrow_case(checker, raw, src_wl, from_frac, f, m);
      }
      samples += checker.samples();
    }
  }
  g_narrow_samples += samples;
  std::printf("[ narrow   ] wide sources: %lld combinations, %lld samples\n", combos, samples);
}

// Wide sources that are shifted left (from_frac < frac_bits), with saturation: the
// model clamps |x * 2^k| at 2^125, which must not change a saturated result.
TEST(FixedPointOracle, NarrowWideSourceLeftShiftSaturates) {
  Rng rng(mix(kSeed, 3));
  SCOPED_TRACE(::testing::Message() << "kSeed=0x" << std::hex << kSeed << " salt 3");
  Checker checker;
  for (const Format& f : all_formats()) {
    for (const Mode& m : kModes) {
      if (m.overflow != Overflow::Saturate) continue;
      for (int n = 0; n < 50 && !checker.exhausted(); ++n) {
        const int src_wl = rng.range(63, 120);
        const int from_frac = f.frac_bits - rng.range(1, 40);
        const Wide raw = random_source(rng, src_wl, from_frac, f);
        check_narrow_case(checker, raw, src_wl, from_frac, f, m);
      }
    }
  }
  g_narrow_samples += checker.samples();
}

// narrow_nearest_saturate(): the walker's inline 64-bit narrowing. Its contract is
// narrow() with Round::Nearest / Overflow::Saturate for a value that fits 64 bits before
// and after the shift; it is checked against SC_RND / SC_SAT (and against narrow()).
TEST(FixedPointOracle, NarrowNearestSaturateMatchesScFix) {
  const Mode& m = kModes[2];  // Nearest/Saturate (SC_RND,SC_SAT)
  long long samples = 0;
  long long combos = 0;
  for (const Format& f : all_formats()) {
    const std::uint64_t seed = combo_seed(f, m, 5);
    SCOPED_TRACE(::testing::Message() << "kSeed=0x" << std::hex << kSeed << " combo seed=0x"
                                      << seed << std::dec << " target " << describe(f)
                                      << " mode " << m.name);
    Rng rng(seed);
    Checker checker;
    ++combos;
    const auto lo = static_cast<std::int64_t>(expected_min_raw(f));
    const auto hi = static_cast<std::int64_t>(expected_max_raw(f));
    for (int n = 0; n < 1000 && !checker.exhausted(); ++n) {
      // |raw| < 2^61 and, for a left shift, |raw| * 2^-shift < 2^62: 64 bits hold both
      // the rounding addend and the result, as the contract requires.
      int src_wl = rng.range(1, 62);
      int from_frac = rng.range(0, 3) != 0 ? src_wl - (f.int_bits + rng.range(-8, 8))
                                           : rng.range(0, 90);
      const int shift = from_frac - f.frac_bits;
      if (shift > 62) from_frac = f.frac_bits + 62;
      if (shift < 0 && src_wl - shift > 62) src_wl = std::max(1, 62 + shift);
      if (src_wl - (from_frac - f.frac_bits) > 62 && from_frac < f.frac_bits) continue;
      const Wide raw = random_source(rng, src_wl, from_frac, f);

      sc_fix src(src_wl, src_wl - from_frac, sc_dt::SC_TRN, sc_dt::SC_WRAP);
      write_raw(src, src_wl, raw);
      const OracleResult o = oracle_cast(src, f, m, src_wl - from_frac);

      bool flag = false;
      const std::int64_t got = cdsim::fx::narrow_nearest_saturate(
          static_cast<std::int64_t>(raw), from_frac - f.frac_bits, lo, hi, &flag);
      bool narrow_flag = false;
      const Wide via_narrow =
          cdsim::fx::narrow(raw, from_frac, f, m.round, m.overflow, &narrow_flag);
      const auto what = [&] {
        std::ostringstream os;
        os << "narrow_nearest_saturate(raw=" << str(raw) << ", shift=" << from_frac - f.frac_bits
           << ", lo=" << lo << ", hi=" << hi << ") into " << describe(f) << "; narrow() gives "
           << str(via_narrow) << " flag " << narrow_flag;
        return os.str();
      };
      checker.check(Wide{got}, flag, o, f, what);
      if (via_narrow != Wide{got} || narrow_flag != flag)
        checker.check(via_narrow, narrow_flag, o, f, what);
    }
    samples += checker.samples();
  }
  g_narrow_samples += samples;
  std::printf("[ narrow64 ] %lld combinations, %lld samples\n", combos, samples);
}

// For a source wider than ~64 bits that narrow() shifts left (from_frac < frac_bits), the
// product does not fit 128 bits; with Overflow::Wrap the low bits must still match SC_WRAP.
TEST(FixedPointOracle, NarrowWrapWideSourceLeftShift) {
  Checker checker;
  const Format f{32, 30, true};  // sc_fix<62,32>
  for (const Mode& m : kModes) {
    // raw = 2^100 + 1 at from_frac 0, into 30 fraction bits: exact value 2^130 + 2^30,
    // whose low 62 bits are 2^30.
    check_narrow_case(checker, (Wide{1} << 100) + 1, 102, 0, f, m);
  }
}

// ---------------------------------------------------------------------------------------
// from_double()

double random_double(Rng& rng, const Format& f) {
  const int kind = rng.range(0, 11);
  const double sign = rng.coin() ? -1.0 : 1.0;
  const int total = f.int_bits + f.frac_bits;
  // A random 53-bit odd-or-even mantissa in [2^52, 2^53).
  const double mantissa =
      static_cast<double>((rng.next() >> 11) | (std::uint64_t{1} << 52));
  switch (kind) {
    case 0:
    case 1: {
      // Exact tie: (2k + 1) / 2 LSB; k has at most 51 bits so the value is exact.
      const int kbits = std::min(total, 51);
      const double k = static_cast<double>(rng.next() >> (64 - kbits));
      return sign * std::ldexp(2.0 * k + 1.0, -(f.frac_bits + 1));
    }
    case 2: {
      // Exact representable value of the format (or of a wider one).
      const int kbits = std::min(total + 2, 53);
      const double k = static_cast<double>(rng.next() >> (64 - kbits));
      return sign * std::ldexp(k, -f.frac_bits);
    }
    case 3: {
      // Next to a tie: one double ulp either side.
      const int kbits = std::min(total, 40);
      const double k = static_cast<double>(rng.next() >> (64 - kbits));
      const double tie = std::ldexp(2.0 * k + 1.0, -(f.frac_bits + 1));
      return sign * (rng.coin() ? std::nextafter(tie, 0.0) : std::nextafter(tie, HUGE_VAL));
    }
    case 4: {
      // Around the range limits: max, max + half LSB, min, min - half LSB, ...
      const double lsb = std::ldexp(1.0, -f.frac_bits);
      const double hi = f.is_signed ? std::ldexp(1.0, f.int_bits - 1) : std::ldexp(1.0, f.int_bits);
      const double lo = f.is_signed ? -hi : 0.0;
      const double base = rng.coin() ? hi : lo;
      return base + lsb * 0.5 * rng.range(-4, 4);
    }
    case 5: {
      // Far outside the range, still a modest magnitude (wraps are meaningful).
      return sign * std::ldexp(mantissa, f.int_bits - 52 + rng.range(0, 12));
    }
    case 6: {
      // Any magnitude at all, down to denormals and up to DBL_MAX.
      return sign * std::ldexp(mantissa, rng.range(-1074 - 52, 1023 - 52));
    }
    default: {
      // Full-precision values around the format's range, many fraction bits below the LSB.
      return sign * std::ldexp(mantissa, f.int_bits - 53 - rng.range(0, f.int_bits + 4));
    }
  }
}

void check_double_case(Checker& checker, double d, const Format& f, const Mode& m) {
  int exponent = 0;
  std::frexp(d, &exponent);  // |d| < 2^exponent
  const OracleResult o = oracle_cast(d, f, m, exponent + 1);
  bool model_flag = false;
  const Wide model_raw = cdsim::fx::from_double(d, f, m.round, m.overflow, &model_flag);
  checker.check(model_raw, model_flag, o, f, [&] {
    std::ostringstream os;
    os << "from_double(" << hex_double(d) << ") into " << describe(f) << " mode " << m.name;
    return os.str();
  });
}

TEST(FixedPointOracle, FromDoubleMatchesScFixOnEveryFormatAndMode) {
  const double specials[] = {0.0,     -0.0,     0.5,      -0.5,     1.5,     -1.5,  2.5,
                             -2.5,    DBL_MIN,  -DBL_MIN, DBL_MAX,  -DBL_MAX, 1e30, -1e30,
                             0x1p-1074, -0x1p-1074, 0x1p62, -0x1p62, 0x1p120, -0x1p121};
  long long combos = 0;
  for (const Format& f : all_formats()) {
    for (const Mode& m : kModes) {
      const std::uint64_t seed = combo_seed(f, m, 4);
      SCOPED_TRACE(::testing::Message() << "kSeed=0x" << std::hex << kSeed << " combo seed=0x"
                                        << seed << std::dec << " target " << describe(f)
                                        << " mode " << m.name);
      Rng rng(seed);
      Checker checker;
      ++combos;
      for (const double d : specials) check_double_case(checker, d, f, m);
      for (int n = 0; n < 1000 && !checker.exhausted(); ++n)
        check_double_case(checker, random_double(rng, f), f, m);
      g_double_samples += checker.samples();
    }
  }
  std::printf("[ from_dbl ] %lld combinations, %lld samples\n", combos, g_double_samples);
}

// Non-finite input is outside sc_fix's domain; the model's documented behaviour is checked
// directly: saturate (NaN -> 0) and raise the flag.
TEST(FixedPointOracle, FromDoubleNonFiniteSaturatesAndFlags) {
  const Format f{17, 12, true};
  for (const Mode& m : kModes) {
    bool flag = false;
    EXPECT_TRUE(cdsim::fx::from_double(HUGE_VAL, f, m.round, m.overflow, &flag) ==
                expected_max_raw(f));
    EXPECT_TRUE(flag);
    flag = false;
    EXPECT_TRUE(cdsim::fx::from_double(-HUGE_VAL, f, m.round, m.overflow, &flag) ==
                expected_min_raw(f));
    EXPECT_TRUE(flag);
    flag = false;
    EXPECT_TRUE(cdsim::fx::from_double(std::numeric_limits<double>::quiet_NaN(), f, m.round,
                                       m.overflow, &flag) == 0);
    EXPECT_TRUE(flag);
  }
}

// ---------------------------------------------------------------------------------------
// The flag is sticky and the comparison can fail.

TEST(FixedPointOracle, OverflowFlagIsStickyAndNotSetInRange) {
  const Format f{8, 8, true};
  bool flag = true;
  cdsim::fx::narrow(Wide{3}, 1, f, Round::Nearest, Overflow::Saturate, &flag);
  EXPECT_TRUE(flag) << "a set flag must stay set";
  flag = false;
  cdsim::fx::narrow(Wide{3}, 1, f, Round::Nearest, Overflow::Saturate, &flag);
  EXPECT_FALSE(flag) << "an in-range value must not raise the flag";
  cdsim::fx::narrow(Wide{1} << 40, 8, f, Round::Nearest, Overflow::Saturate, &flag);
  EXPECT_TRUE(flag);
}

// The oracle distinguishes the modes: a deliberately mismatched pairing must disagree.
TEST(FixedPointOracle, SanityMismatchedModesDisagree) {
  const Format f{8, 0, true};  // sc_fix<8,8>
  const Mode& trn_sat = kModes[0];
  const Mode& rnd_sat = kModes[2];
  const Mode& rnd_wrap = kModes[3];
  // 1.5 (raw 3 at one fraction bit) is a tie: Trunc gives 1, SC_RND gives 2.
  sc_fix src(8, 7, sc_dt::SC_TRN, sc_dt::SC_WRAP);
  write_raw(src, 8, Wide{3});
  const OracleResult rnd = oracle_cast(src, f, rnd_sat, 7);
  bool flag = false;
  const Wide trunc = cdsim::fx::narrow(Wide{3}, 1, f, trn_sat.round, trn_sat.overflow, &flag);
  EXPECT_EQ(str(rnd.raw), "2");
  EXPECT_EQ(str(trunc), "1");
  EXPECT_NE(str(trunc), str(rnd.raw)) << "Trunc must differ from SC_RND on a tie";
  // A tie below zero: -1.5 -> SC_RND gives -1 (toward +inf), not -2 (away from zero).
  EXPECT_EQ(str(oracle_cast(-1.5, f, rnd_sat, 2).raw), "-1");
  // 200 into sc_fix<8,8>: Saturate gives 127, SC_WRAP gives -56.
  const Wide sat = cdsim::fx::from_double(200.0, f, Round::Nearest, Overflow::Saturate, &flag);
  const OracleResult wrap = oracle_cast(200.0, f, rnd_wrap, 9);
  EXPECT_EQ(str(sat), "127");
  EXPECT_EQ(str(wrap.raw), "-56");
  EXPECT_NE(str(sat), str(wrap.raw)) << "Saturate must differ from SC_WRAP on overflow";
  // And the Checker itself reports a mismatch.
  Checker checker;
  bool reported = false;
  {
    ::testing::TestPartResultArray failures;
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
    checker.check(trunc, false, rnd, f, [] { return std::string("deliberate mismatch"); });
    reported = failures.size() == 1;
  }
  EXPECT_TRUE(reported) << "the checker must flag Trunc vs SC_RND on a tie";
}

}  // namespace
