#include "strict_text.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace cdsim {

std::string_view without_utf8_bom(std::string_view text) {
  if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  return text;
}

std::string quote_bytes(std::string_view text, size_t max_bytes, char quote) {
  std::string out(1, quote);
  for (size_t i = 0; i < text.size() && i < max_bytes; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte == '\t') {
      out += "\\t";
    } else if (byte == '\r') {
      out += "\\r";
    } else if (byte == '\n') {
      out += "\\n";
    } else if (byte == '\\' || byte == static_cast<unsigned char>(quote)) {
      out += '\\';
      out += static_cast<char>(byte);
    } else if (byte < 0x20 || byte >= 0x7f) {
      out += fmt::format("\\x{:02x}", byte);
    } else {
      out += static_cast<char>(byte);
    }
  }
  out += quote;
  if (text.size() > max_bytes) out += fmt::format(" (cut; {} bytes in all)", text.size());
  return out;
}

ParsedNumber parse_number(std::string_view token, double limit) {
  ParsedNumber out;
  out.limit = limit;
  std::string_view digits = token;
  // from_chars takes no '+'; a sign after it ("+-1", "++1") stays an error.
  if (!digits.empty() && digits[0] == '+') {
    digits.remove_prefix(1);
    if (!digits.empty() && (digits[0] == '+' || digits[0] == '-')) digits = {};
  }
  if (digits.empty()) {
    out.problem = NumberProblem::kNotANumber;
    return out;
  }
  const char* first = digits.data();
  const char* last = first + digits.size();
  double value = 0;
  const auto [end, error] = std::from_chars(first, last, value, std::chars_format::general);
  if (end != last || error == std::errc::invalid_argument) {
    out.problem = NumberProblem::kNotANumber;
    return out;
  }
  if (error == std::errc::result_out_of_range) {
    // Overflow or underflow: strtod tells them apart (HUGE_VAL for overflow).
    const std::string copy(digits);
    errno = 0;
    value = std::strtod(copy.c_str(), nullptr);
    if (std::isinf(value)) {
      out.problem = NumberProblem::kOutOfRange;
      return out;
    }
  }
  if (!std::isfinite(value)) {
    out.problem = NumberProblem::kNotFinite;
    return out;
  }
  if (std::fabs(value) > limit) {
    out.problem = NumberProblem::kOutOfRange;
    return out;
  }
  out.value = value;
  return out;
}

std::string number_problem(const ParsedNumber& parsed, std::string_view token) {
  switch (parsed.problem) {
    case NumberProblem::kNone:
      return fmt::format("{} is a number", quote_bytes(token));
    case NumberProblem::kNotANumber:
      return fmt::format("{} is not a number", quote_bytes(token));
    case NumberProblem::kNotFinite:
      return fmt::format("{} is not a finite number", quote_bytes(token));
    case NumberProblem::kOutOfRange:
      break;
  }
  return fmt::format("{} is out of range: its magnitude exceeds {:g}", quote_bytes(token), parsed.limit);
}

std::optional<long long> parse_integer(std::string_view token) {
  if (!token.empty() && token[0] == '+') {
    token.remove_prefix(1);
    if (!token.empty() && (token[0] == '+' || token[0] == '-')) return std::nullopt;
  }
  if (token.empty()) return std::nullopt;
  long long value = 0;
  const char* last = token.data() + token.size();
  const auto [end, error] = std::from_chars(token.data(), last, value);
  if (error != std::errc() || end != last) return std::nullopt;
  return value;
}

}  // namespace cdsim
