// Strict checks for cdsim's command line, as CLI11 validators: numbers in
// plain decimal (no hex, octal, exponent, sign '+' or spaces for integers),
// finite, and within each option's range; every message names the option
// (CLI11 prefixes it) and the value.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>

namespace cdsim::cli {

// A decimal integer in [lo, hi].
CLI::Validator integer_in(int64_t lo, int64_t hi);
// A decimal integer without sign in [lo, hi] (seeds and counts: fits uint64).
CLI::Validator unsigned_in(uint64_t lo, uint64_t hi);
// A finite decimal number in the range; an open end excludes its bound.
CLI::Validator number_in(double lo, double hi, bool lo_open = false, bool hi_open = false);

// Applies to every option of app and of its subcommands, including those
// declared elsewhere (scene options, area):
//  - integers of any type: integer_in / unsigned_in over the full 64-bit range
//    (CLI11 itself refuses values that do not fit a narrower type);
//  - floating-point numbers: finite;
//  - values: not empty;
//  - single-valued options and flags: given at most once (MultiOptionPolicy::Throw).
// Options that take a list (--set) stay repeatable. Call after every option is added.
void make_strict(CLI::App& app);

}  // namespace cdsim::cli
