#include "encodings.hpp"

#include <fmt/format.h>

#include <map>
#include <utility>

namespace cdsim::encoding {

static_assert(consistent(), "encodings.def: a code repeats, lies outside its group's field, or has no group");

std::string rtl_defines() {
  std::string out;
  for (const Group& g : kGroups) {
    out += fmt::format("// {} ({})\n", g.meaning, g.is_position ? "bit positions" : "values");
    out += fmt::format("`define CD_{}_BITS {}\n", g.name, g.bits);
    out += fmt::format("`define CD_{}_COUNT {}\n", g.name, count_of(g.name));
    for (const Code& c : kCodes)
      if (c.group == g.name) out += fmt::format("`define CD_{}_{} {}\n", c.group, c.name, c.value);
  }
  return out;
}

const char* lower_name(std::string_view group, int value) {
  static const std::map<std::pair<std::string_view, int>, std::string> names = [] {
    std::map<std::pair<std::string_view, int>, std::string> m;
    for (const Code& c : kCodes) {
      std::string name(c.name);
      for (char& ch : name) ch = static_cast<char>(ch >= 'A' && ch <= 'Z' ? ch - 'A' + 'a' : ch);
      m.emplace(std::make_pair(c.group, c.value), std::move(name));
    }
    return m;
  }();
  const auto it = names.find({group, value});
  return it == names.end() ? "unknown" : it->second.c_str();
}

}  // namespace cdsim::encoding
