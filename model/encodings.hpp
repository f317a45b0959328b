// The encodings the twins and the harness share (encodings.def): design
// kinds, the scan unit's state encodings, the flag bits and the observation
// ports' bit positions, as encoding::<GROUP>_<NAME>, the names the RTL reads
// as `CD_<GROUP>_<NAME>` from the generated cd_widths.svh.
#pragma once

#include <string>
#include <string_view>

namespace cdsim::encoding {

#define CDSIM_ENCODING_GROUP(group, bits, is_position, meaning) inline constexpr int group##_BITS = bits;
#define CDSIM_ENCODING(group, name, value, meaning) inline constexpr int group##_##name = value;
#include "encodings.def"
#undef CDSIM_ENCODING
#undef CDSIM_ENCODING_GROUP

struct Group {
  std::string_view name;
  int bits;
  bool is_position;  // the values are bit positions in a field of `bits` bits
  std::string_view meaning;
};
struct Code {
  std::string_view group;
  std::string_view name;
  int value;
  std::string_view meaning;
};

inline constexpr Group kGroups[] = {
#define CDSIM_ENCODING_GROUP(group, bits, is_position, meaning) {#group, bits, is_position, meaning},
#define CDSIM_ENCODING(group, name, value, meaning)
#include "encodings.def"
#undef CDSIM_ENCODING
#undef CDSIM_ENCODING_GROUP
};
inline constexpr Code kCodes[] = {
#define CDSIM_ENCODING_GROUP(group, bits, is_position, meaning)
#define CDSIM_ENCODING(group, name, value, meaning) {#group, #name, value, meaning},
#include "encodings.def"
#undef CDSIM_ENCODING
#undef CDSIM_ENCODING_GROUP
};

// The number of codes in a group.
constexpr int count_of(std::string_view group) {
  int n = 0;
  for (const Code& c : kCodes) n += c.group == group ? 1 : 0;
  return n;
}

// Whether every group's codes are distinct and fit its field: a position
// below `bits`, a value below 2^bits. A static_assert in encodings.cpp.
constexpr bool consistent() {
  for (const Group& g : kGroups)
    for (const Code& a : kCodes) {
      if (a.group != g.name) continue;
      const long long limit = g.is_position ? g.bits : (1LL << g.bits);
      if (a.value < 0 || a.value >= limit) return false;
      for (const Code& b : kCodes)
        if (&a != &b && b.group == a.group && (b.value == a.value || b.name == a.name)) return false;
    }
  for (const Code& c : kCodes) {
    bool grouped = false;
    for (const Group& g : kGroups) grouped = grouped || g.name == c.group;
    if (!grouped) return false;
  }
  return true;
}

// The table as `define CD_<GROUP>_<NAME> lines, with CD_<GROUP>_BITS and
// CD_<GROUP>_COUNT, for cd_widths.svh.
std::string rtl_defines();
// A code's name in lower case ("table_saturated"), or "unknown".
const char* lower_name(std::string_view group, int value);

}  // namespace cdsim::encoding
