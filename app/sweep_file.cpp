#include "sweep_file.hpp"

#include <fmt/format.h>

#include <charconv>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include "design.hpp"
#include "widths.hpp"

namespace cdsim {

namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

// A decimal integer, as the whole of `text` (spaces around it aside).
int parse_int(const std::string& raw, const std::string& context) {
  const std::string text = trim(raw);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error == std::errc::invalid_argument || end != text.data() + text.size())
    throw std::invalid_argument(fmt::format("sweep setting '{}': '{}' is not an integer", context, text));
  if (error == std::errc::result_out_of_range)
    throw std::invalid_argument(fmt::format("sweep setting '{}': {} is out of range", context, text));
  return value;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t at = text.find(separator, start);
    parts.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

}  // namespace

SweepAxis parse_axis(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || trim(text.substr(0, eq)).empty())
    throw std::invalid_argument(
        fmt::format("sweep setting '{}' is not NAME=LO:HI[:STEP], NAME=A,B or NAME=V", text));
  SweepAxis axis{trim(text.substr(0, eq)), {}};
  const std::string values = text.substr(eq + 1);
  Widths probe;
  if (values.find(':') != std::string::npos) {
    const auto parts = split(values, ':');
    if (parts.size() < 2 || parts.size() > 3)
      throw std::invalid_argument(fmt::format("sweep setting '{}': expected LO:HI or LO:HI:STEP", text));
    const int lo = parse_int(parts[0], text), hi = parse_int(parts[1], text);
    const int step = parts.size() == 3 ? parse_int(parts[2], text) : 1;
    if (step <= 0) throw std::invalid_argument(fmt::format("sweep setting '{}': STEP must be positive", text));
    if (hi < lo) throw std::invalid_argument(fmt::format("sweep setting '{}': HI is below LO", text));
    // Both ends in range first (throws naming the range), so the expansion is bounded.
    set_param(probe, axis.name, lo);
    set_param(probe, axis.name, hi);
    for (int64_t v = lo; v <= hi; v += step) axis.values.push_back(int(v));
  } else {
    std::set<int> seen;
    for (const auto& part : split(values, ',')) {
      const int v = parse_int(part, text);
      if (!seen.insert(v).second)
        throw std::invalid_argument(fmt::format("sweep setting '{}': the value {} is listed twice", text, v));
      set_param(probe, axis.name, v);
      axis.values.push_back(v);
    }
  }
  return axis;
}

SweepFile parse_sweep_file(std::istream& in, const std::string& name) {
  SweepFile file;
  std::map<std::string, int> axis_line;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);  // UTF-8 BOM
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    line = trim(line);
    if (line.empty()) continue;
    try {
      const auto space = line.find_first_of(" \t");
      if (line.substr(0, space) == "design") {
        if (file.design_line)
          throw std::invalid_argument(
              fmt::format("a second 'design' line (the first is line {})", file.design_line));
        file.designs = space == std::string::npos ? "" : trim(line.substr(space));
        if (file.designs.empty()) throw std::invalid_argument("'design' needs a LIST of designs");
        parse_design_list(file.designs);
        file.design_line = number;
      } else {
        SweepAxis axis = parse_axis(line);
        if (const auto it = axis_line.find(axis.name); it != axis_line.end())
          throw std::invalid_argument(
              fmt::format("parameter {} is swept twice (first at line {})", axis.name, it->second));
        axis_line[axis.name] = number;
        file.axes.push_back(std::move(axis));
        file.axis_lines.push_back(number);
      }
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("{}:{}: {}", name, number, e.what()));
    }
  }
  if (in.bad()) throw std::invalid_argument(fmt::format("{}:{}: read error", name, number + 1));
  if (file.axes.empty() && file.designs.empty())
    throw std::invalid_argument(
        fmt::format("{}:{}: no parameter and no 'design' line: nothing to sweep", name, number));
  return file;
}

uint64_t sweep_size(size_t designs, const std::vector<SweepAxis>& axes) {
  uint64_t n = designs;
  for (const SweepAxis& axis : axes)
    if (__builtin_mul_overflow(n, uint64_t(axis.values.size()), &n))
      return std::numeric_limits<uint64_t>::max();
  return n;
}

}  // namespace cdsim
