#include "cli_checks.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <string>

namespace cdsim::cli {

namespace {

// Digits with an optional leading '-', and no leading zero (which strtol's
// base 0, as CLI11 converts, would read as octal).
bool is_decimal_integer(const std::string& text, bool allow_minus) {
  size_t i = allow_minus && !text.empty() && text[0] == '-' ? 1 : 0;
  if (i == text.size()) return false;
  if (text[i] == '0' && text.size() > i + 1) return false;
  for (; i < text.size(); ++i)
    if (text[i] < '0' || text[i] > '9') return false;
  return true;
}

template <class T>
std::string check_integer(const std::string& text, T lo, T hi) {
  constexpr bool is_signed = std::numeric_limits<T>::is_signed;
  if (!is_signed && !text.empty() && text[0] == '-') return fmt::format("'{}' is negative", text);
  if (!is_decimal_integer(text, is_signed)) return fmt::format("'{}' is not a decimal integer", text);
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range || value < lo || value > hi)
    return fmt::format("{} is out of range: must be in [{}, {}]", text, lo, hi);
  return "";
}

std::string type_of(const CLI::Option* option) {
  const std::string name = option->get_type_name();
  return name.substr(0, name.find(':'));
}

}  // namespace

CLI::Validator integer_in(int64_t lo, int64_t hi) {
  return CLI::Validator([lo, hi](std::string& text) { return check_integer<int64_t>(text, lo, hi); },
                        fmt::format("in [{}, {}]", lo, hi));
}

CLI::Validator unsigned_in(uint64_t lo, uint64_t hi) {
  return CLI::Validator([lo, hi](std::string& text) { return check_integer<uint64_t>(text, lo, hi); },
                        fmt::format("in [{}, {}]", lo, hi));
}

CLI::Validator number_in(double lo, double hi, bool lo_open, bool hi_open) {
  // "in [0, 0.95]", "in (0, 3600]", "> 0"
  std::string range =
      fmt::format("in {}{}, {}{}", lo_open ? '(' : '[', lo, hi, hi_open ? ')' : ']');
  if (std::isinf(hi) && !std::isinf(lo)) range = fmt::format("{} {}", lo_open ? ">" : ">=", lo);
  const std::string description = std::isinf(lo) && std::isinf(hi) ? std::string() : range;
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        double value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (text.empty() || end != text.data() + text.size() ||
            (error != std::errc() && error != std::errc::result_out_of_range))
          return fmt::format("'{}' is not a number", text);
        if (error == std::errc::result_out_of_range)
          return fmt::format("'{}' is beyond the range of a double", text);
        if (!std::isfinite(value)) return fmt::format("'{}' is not a finite number", text);
        if (value < lo || value > hi || (lo_open && value == lo) || (hi_open && value == hi))
          return fmt::format("{} is out of range: must be {}", text, range);
        return "";
      },
      description);
}

void make_strict(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option == app.get_help_ptr() || option == app.get_help_all_ptr()) continue;
    const bool takes_value = option->get_expected_min() > 0 || option->get_expected_max() > 0;
    if (!takes_value || option->get_items_expected_max() <= 1)
      option->multi_option_policy(CLI::MultiOptionPolicy::Throw);
    if (!takes_value) continue;
    const std::string type = type_of(option);
    // Without a description: the option's own range, if any, is what --help shows.
    if (type == "INT")
      option->check(integer_in(std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max())
                        .description(""));
    else if (type == "UINT")
      option->check(unsigned_in(0, std::numeric_limits<uint64_t>::max()).description(""));
    else if (type == "FLOAT")
      option->check(number_in(-std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::infinity()));
    option->check(CLI::Validator(
        [](std::string& text) { return text.empty() ? std::string("the value is empty") : std::string(); },
        ""));
  }
  for (CLI::App* sub : app.get_subcommands({})) make_strict(*sub);
}

}  // namespace cdsim::cli
