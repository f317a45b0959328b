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
  Wide max_raw() const;
  Wide min_raw() const;
};

// x * 2^-shift, rounded as asked; a negative shift multiplies exactly.
Wide shift_round(Wide x, int shift, Round round);

// Fits raw into format. Returns the fitted value and sets *overflowed when
// raw lay outside the format's range (the flag is sticky: it is never cleared).
Wide fit(Wide raw, const Format& format, Overflow overflow, bool* overflowed);

// Re-scales raw from from_frac fraction bits to format, then fits it.
Wide narrow(Wide raw, int from_frac, const Format& format, Round round, Overflow overflow,
            bool* overflowed);

// Quantises a double into format (used at the unit boundary and by tests).
// Non-finite input saturates and sets *overflowed.
Wide from_double(double value, const Format& format, Round round, Overflow overflow,
                 bool* overflowed);

double to_double(Wide raw, int frac_bits);

// Number of bits needed to write |x| (0 for x == 0).
int bit_length(Wide x);

// Floor division for any signs (C++ '/' truncates toward zero).
Wide floor_div(Wide numerator, Wide denominator);
Wide ceil_div(Wide numerator, Wide denominator);

}  // namespace cdsim::fx
