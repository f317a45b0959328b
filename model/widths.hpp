// Widths and microarchitecture parameters of the unit, from widths.def.
#pragma once

#include <string>
#include <vector>

#include "fixed.hpp"

namespace cdsim {

struct Widths {
#define CDSIM_PARAM(name, def, lo, hi, doc) int name = def;
#include "widths.def"
#undef CDSIM_PARAM

  // The line phase's fraction bits as the unit uses them: at most g_frac,
  // since the phase starts the walker's m g o, which has g_frac fraction bits.
  int line_phase_frac() const { return line_phase_bits < g_frac ? line_phase_bits : g_frac; }
  fx::Format t_format() const { return {t_int, t_frac, true}; }
  fx::Format s_format() const { return {s_int, s_frac, true}; }
  fx::Format out_format() const { return {out_int, out_frac, true}; }
  // Table word: T.u, T.v, S.u, S.v, and for cd-persp eps (s<eps_int>.eps_frac).
  int table_word_bits(bool persp = false) const {
    return 2 * (t_int + t_frac) + 2 * (s_int + s_frac) + (persp ? eps_int + eps_frac : 0);
  }
};

struct ParamInfo {
  const char* name;
  int default_value;
  int min_value;
  int max_value;
  const char* meaning;
  int Widths::*field;
};

const std::vector<ParamInfo>& param_table();

// Applies "NAME=VALUE". Throws std::invalid_argument naming the parameter and
// the allowed range when the name is unknown or the value is out of range.
void apply_setting(Widths& widths, const std::string& assignment);
// Applies each "NAME=VALUE" of a repeatable --set in turn; a parameter named
// twice is refused (std::invalid_argument naming both settings), not the
// later one silently taken.
void apply_settings(Widths& widths, const std::vector<std::string>& assignments);
void set_param(Widths& widths, const std::string& name, long long value);
// Checks combinations that single ranges cannot (for example the accumulator
// fitting 64 bits). Throws std::invalid_argument.
void validate(const Widths& widths);

std::string describe(const Widths& widths);  // "subpixel_bits=8 uv_in_frac=8 ..."

// The adaptive design's leaf unit (model/adaptive_split.hpp): vertices with
// adapt_depth more subpixel bits (a midpoint of midpoints is exact there) and
// u, v with adapt_uv_extra more fraction bits. Past widths.def's ranges by
// design; validate() the widths it is made from.
Widths adaptive_leaf_widths(const Widths& widths);

}  // namespace cdsim
