#include "correction_adder.hpp"

namespace cdsim {

CorrectedValue correction_adder(const LineValue& own, const LineValue& neighbour, int64_t weight,
                                const Widths& w) {
  const int frac = accumulator_frac(w);
  const auto correct = [&](int64_t a, int64_t b) {
    return fx::Wide{a} + fx::shift_round(fx::Wide{weight} * (b - a), w.d_frac, fx::Round::Nearest);
  };
  CorrectedValue out;
  const fx::Format format = w.out_format();
  out.u = static_cast<int64_t>(fx::narrow(correct(own.u, neighbour.u), frac, format,
                                          fx::Round::Nearest, fx::Overflow::Saturate, &out.saturated));
  out.v = static_cast<int64_t>(fx::narrow(correct(own.v, neighbour.v), frac, format,
                                          fx::Round::Nearest, fx::Overflow::Saturate, &out.saturated));
  return out;
}

}  // namespace cdsim
