#include "fixed.hpp"

#include <cmath>

namespace cdsim::fx {

namespace {
const Wide kWideLimit = Wide{1} << 125;
}  // namespace

Wide floor_div(Wide numerator, Wide denominator) {
  Wide quotient = numerator / denominator;
  if ((numerator % denominator != 0) && ((numerator < 0) != (denominator < 0))) --quotient;
  return quotient;
}

Wide ceil_div(Wide numerator, Wide denominator) { return -floor_div(-numerator, denominator); }

Wide shift_left_clamped(Wide x, int shift) {
  // A left shift past 125 bits can only feed a saturation; clamp instead of overflowing.
  if (x != 0 && bit_length(x) + shift > 125) return x > 0 ? kWideLimit : -kWideLimit;
  return x * (Wide{1} << shift);
}

Wide wrap(Wide raw, const Format& format) {
  // Keep the low total_bits bits, then sign-extend for signed formats.
  const Wide modulus = Wide{1} << format.total_bits();
  Wide low = raw & (modulus - 1);
  if (format.is_signed && low >= (modulus >> 1)) low -= modulus;
  return low;
}

Wide wrap_huge_left_shift(Wide raw, int shift, const Format& format, bool* overflowed) {
  // |raw * 2^shift| > 2^125 lies far outside any format, so it always overflows.
  if (overflowed) *overflowed = true;
  const Wide low = raw & ((Wide{1} << 64) - 1);
  return wrap(shift >= format.total_bits() ? 0 : low * (Wide{1} << shift), format);
}

Wide from_double(double value, const Format& format, Round round, Overflow overflow,
                 bool* overflowed) {
  if (!std::isfinite(value)) {
    if (overflowed) *overflowed = true;
    if (std::isnan(value)) return 0;
    return value > 0 ? format.max_raw() : format.min_raw();
  }
  const long double scaled = std::ldexp(static_cast<long double>(value), format.frac_bits);
  long double rounded =
      round == Round::Nearest ? std::floor(scaled + 0.5L) : std::floor(scaled);
  // Clamp before converting so that the conversion itself cannot overflow.
  const long double limit = std::ldexp(1.0L, 120);
  if (rounded > limit) rounded = limit;
  if (rounded < -limit) rounded = -limit;
  return fit(static_cast<Wide>(rounded), format, overflow, overflowed);
}

double to_double(Wide raw, int frac_bits) {
  return static_cast<double>(std::ldexp(static_cast<long double>(raw), -frac_bits));
}

}  // namespace cdsim::fx
