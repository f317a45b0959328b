// Widths the hardware derives from model/widths.def: the bit count of every
// register, wire and operator of the scan unit, and the cycle budgets that
// follow from its structure. Defined once, here. The RTL reads them as
// `define CD_<NAME> from the generated cd_widths.svh (rtl_header below);
// the model reads them too and checks every intermediate value against its
// width (fits_or_throw), so a derivation that is too narrow fails a test
// instead of silently truncating in the RTL.
//
// Bit counts are two's-complement widths (sign included) unless the name
// says unsigned. Bounds come from the input ranges of SPEC §1 and §4:
// |x|, |y| < 2^15 pixels, |u|, |v| < 2^15 texels, viewport <= 8192, box
// offsets < 2^13, density m <= 4, |g| <= 1. docs/rtl.md gives the reasoning.
#pragma once

#include <string>
#include <vector>

#include "fixed.hpp"
#include "widths.hpp"

namespace cdsim {

struct DerivedWidths {
#define CDSIM_DERIVED(name, doc) int name = 0;
#include "derived_widths.def"
#undef CDSIM_DERIVED
};

DerivedWidths derive(const Widths& widths);

// The table word the unit stores for a design, flags included: cd-persp's
// holds eps and its saturation bit as well.
inline int unit_word_bits(const DerivedWidths& d, bool persp) { return persp ? d.persp_word_bits : d.word_bits; }

struct DerivedInfo {
  const char* name;
  const char* meaning;
  int DerivedWidths::*field;
};
const std::vector<DerivedInfo>& derived_table();

// The generated SystemVerilog header of one width configuration: every base
// parameter of widths.def, every derived width, the flag bits and the table
// word layout, as `define CD_<NAME> value.
std::string rtl_header(const Widths& widths, const std::string& config);

// Throws std::logic_error naming the quantity when raw needs more than bits
// (signed two's complement). A failure means a derived width is wrong.
void fits_or_throw(fx::Wide raw, int bits, const char* what);
void fits_unsigned_or_throw(fx::Wide raw, int bits, const char* what);

}  // namespace cdsim
