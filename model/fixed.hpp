// Fixed-point layer of the cdsim model.
//
// Values are plain integers ("raw") scaled by 2^-frac_bits. Formats are runtime
// values, so a width sweep needs no rebuild. Following pico-gs's qfixed, an
// operation never loses bits by accident: additions and products are exact in a
// wide integer, and every narrowing is one explicit call that names its rounding
// and its overflow behaviour and reports overflow to the caller.
//
// Conventions follow SystemC's sc_fix so that sc_fix is a direct oracle:
//   int_bits counts the sign bit of a signed format (SystemC's iwl);
//   Round::Trunc   == SC_TRN  (toward minus infinity),
//   Round::Nearest == SC_RND  (to nearest, ties toward plus infinity);
//   Overflow::Saturate == SC_SAT, Overflow::Wrap == SC_WRAP.
#pragma once

#include <cstdint>

namespace cdsim::fx {

__extension__ typedef __int128 Wide;  // exact intermediate products and sums

enum class Round { Trunc, Nearest };
enum class Overflow { Saturate, Wrap };

struct Format {
  int int_bits = 0;   // integer bits, sign bit included for signed formats
  int frac_bits = 0;  // fraction bits
  bool is_signed = true;

  int total_bits() const { return int_bits + frac_bits; }
  inline Wide max_raw() const;
  inline Wide min_raw() const;
};

// x * 2^-shift, rounded as asked; a negative shift multiplies exactly.
inline Wide shift_round(Wide x, int shift, Round round);

// Fits raw into format. Returns the fitted value and sets *overflowed when
// raw lay outside the format's range (the flag is sticky: it is never cleared).
inline Wide fit(Wide raw, const Format& format, Overflow overflow, bool* overflowed);

// Re-scales raw from from_frac fraction bits to format, then fits it.
inline Wide narrow(Wide raw, int from_frac, const Format& format, Round round, Overflow overflow,
                   bool* overflowed);

// Quantises a double into format (used at the unit boundary and by tests).
// Non-finite input saturates and sets *overflowed.
Wide from_double(double value, const Format& format, Round round, Overflow overflow,
                 bool* overflowed);

double to_double(Wide raw, int frac_bits);

// Number of bits needed to write |x| (0 for x == 0), by counting leading
// zeros, as a priority encoder would.
inline int bit_length(Wide x) {
  __extension__ typedef unsigned __int128 UWide;
  const UWide magnitude = x < 0 ? UWide{0} - static_cast<UWide>(x) : static_cast<UWide>(x);
  const auto high = static_cast<uint64_t>(magnitude >> 64), low = static_cast<uint64_t>(magnitude);
  if (high != 0) return 128 - __builtin_clzll(high);
  return low != 0 ? 64 - __builtin_clzll(low) : 0;
}

// Floor division for any signs (C++ '/' truncates toward zero).
Wide floor_div(Wide numerator, Wide denominator);
Wide ceil_div(Wide numerator, Wide denominator);

// The same as narrow() with Round::Nearest and Overflow::Saturate for a value
// that fits Int (int64_t or Wide) before and after the shift (the walker's
// accumulator: column_walker.hpp, walker_bits, picks Int). Bounds are the
// format's raw range.
inline int64_t left_shift(int64_t x, int shift) {
  return static_cast<int64_t>(static_cast<uint64_t>(x) << shift);
}
inline Wide left_shift(Wide x, int shift) {
  __extension__ typedef unsigned __int128 UWide;
  return static_cast<Wide>(static_cast<UWide>(x) << shift);
}
template <class Int>
inline int64_t narrow_nearest_saturate(Int raw, int shift, int64_t lo, int64_t hi, bool* overflowed) {
  const Int scaled = shift > 0 ? (raw + (Int{1} << (shift - 1))) >> shift : left_shift(raw, -shift);
  if (scaled > hi) return *overflowed = true, hi;
  if (scaled < lo) return *overflowed = true, lo;
  return static_cast<int64_t>(scaled);
}

// Out of line: the rare paths (a left shift past 125 bits, wrapping).
Wide shift_left_clamped(Wide x, int shift);
Wide wrap(Wide raw, const Format& format);
// Wrapping raw * 2^shift when the product would not fit 128 bits: only its low
// bits matter, so shift the low 64 bits of raw (formats are at most 62 bits).
Wide wrap_huge_left_shift(Wide raw, int shift, const Format& format, bool* overflowed);

// Inline because they sit on the walker's per-pixel path.
inline Wide Format::max_raw() const {
  return (Wide{1} << (is_signed ? total_bits() - 1 : total_bits())) - 1;
}
inline Wide Format::min_raw() const { return is_signed ? -(Wide{1} << (total_bits() - 1)) : 0; }

inline Wide shift_round(Wide x, int shift, Round round) {
  if (shift <= 0) return shift_left_clamped(x, -shift);
  // |x| < 2^127, so from a shift of 127 on only the sign survives (and, to
  // nearest, nothing); shifting a 128-bit value that far is undefined in C++.
  if (shift >= 127) return round == Round::Nearest || x >= 0 ? 0 : -1;
  // Arithmetic right shift floors; adding half first rounds ties toward +inf.
  if (round == Round::Nearest) x += Wide{1} << (shift - 1);
  return x >> shift;
}

inline Wide fit(Wide raw, const Format& format, Overflow overflow, bool* overflowed) {
  const Wide hi = format.max_raw();
  const Wide lo = format.min_raw();
  if (raw >= lo && raw <= hi) return raw;
  if (overflowed) *overflowed = true;
  if (overflow == Overflow::Saturate) return raw > hi ? hi : lo;
  return wrap(raw, format);
}

inline Wide narrow(Wide raw, int from_frac, const Format& format, Round round, Overflow overflow,
                   bool* overflowed) {
  const int shift = from_frac - format.frac_bits;
  if (shift < 0 && overflow == Overflow::Wrap && raw != 0 && bit_length(raw) - shift > 125)
    return wrap_huge_left_shift(raw, -shift, format, overflowed);
  return fit(shift_round(raw, shift, round), format, overflow, overflowed);
}

}  // namespace cdsim::fx
