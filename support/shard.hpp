// --shard I/N of sweep and regress: the I-th of N shards (1-based) takes every
// N-th item from the (I-1)-th, so that each item is in exactly one shard and
// items keep their seeds and order. `cdsim merge` joins the shards' outputs.
#pragma once

#include <fmt/format.h>

#include <charconv>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

namespace cdsim {

struct Shard {
  uint64_t index = 1, count = 1;  // a default Shard is the whole run
  bool whole() const { return count == 1; }
  bool holds(uint64_t item) const { return item % count == index - 1; }
};

// Parses "I/N" (1 <= I <= N <= 10^6); throws std::invalid_argument naming the option.
inline Shard parse_shard(const std::string& option, const std::string& text) {
  const auto number = [&](std::string_view part, uint64_t& value) {
    if (part.empty() || part.size() > 7 || part.find_first_not_of("0123456789") != std::string_view::npos)
      return false;
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    return error == std::errc() && end == part.data() + part.size();
  };
  const size_t slash = text.find('/');
  Shard s;
  if (slash == std::string::npos || !number(std::string_view(text).substr(0, slash), s.index) ||
      !number(std::string_view(text).substr(slash + 1), s.count) || s.count < 1 || s.count > 1'000'000 ||
      s.index < 1 || s.index > s.count)
    throw std::invalid_argument(fmt::format(
        "{} '{}': expected I/N, the I-th of N shards, with 1 <= I <= N <= 1000000", option, text));
  return s;
}

}  // namespace cdsim
