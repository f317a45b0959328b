// Strict reading of the text formats (.tri, .obj, .mtl, .json, .gltf): a
// number is the whole token or nothing, never a prefix, never NaN or
// infinity, never a value beyond the range it is stored in; a UTF-8
// byte-order mark at the start of a file is ignored; and every byte of the
// input that a message repeats is escaped, so that a NUL or a control
// character cannot cut the message short.
#pragma once

#include <cfloat>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace cdsim {

// `text` without a leading UTF-8 byte-order mark (EF BB BF).
std::string_view without_utf8_bom(std::string_view text);

// `text` in quotes (`quote`) for a message: printable ASCII as it is, every
// other byte as \xNN (\t, \r and \n as such); longer than `max_bytes` it is
// cut there and its length given.
std::string quote_bytes(std::string_view text, size_t max_bytes = 40, char quote = '\'');

enum class NumberProblem { kNone, kNotANumber, kNotFinite, kOutOfRange };

struct ParsedNumber {
  double value = 0;
  NumberProblem problem = NumberProblem::kNone;
  double limit = DBL_MAX;  // the magnitude it was checked against
  bool ok() const { return problem == NumberProblem::kNone; }
};

// A decimal floating-point number that is the whole of `token` (the syntax of
// std::from_chars, general format, with an optional leading '+'), finite and
// at most `limit` in magnitude. An underflow (a value that rounds to zero or
// to a subnormal) is a finite number and accepted.
ParsedNumber parse_number(std::string_view token, double limit = DBL_MAX);

// What is wrong with `token`, for a message: "'x' is not a number", "'nan' is
// not a finite number", "'1e999' is out of range: its magnitude exceeds 1.79769e+308".
std::string number_problem(const ParsedNumber& parsed, std::string_view token);

// A decimal integer (optional sign) that is the whole of `token` and fits a
// long long; nothing otherwise.
std::optional<long long> parse_integer(std::string_view token);

// Splits `line` at blanks (space, tab, CR, vertical tab, form feed).
template <typename Visit>
void for_each_word(std::string_view line, Visit&& visit) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && blank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !blank(line[i])) ++i;
    if (i > start) visit(line.substr(start, i - start));
  }
}

}  // namespace cdsim
