// Sweep settings, from `cdsim sweep --set` or a sweep file (--file):
// NAME=LO:HI[:STEP], NAME=A,B,C or NAME=V. A sweep file holds one per line,
// at most one 'design LIST' line, '#' comments and blank lines, and may start
// with a UTF-8 byte-order mark. Every value is a decimal integer in the
// parameter's range (checked before a range is expanded), a list names each
// value once, and a parameter is swept once: a second line for it is refused.
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

namespace cdsim {

// One sweep axis: a parameter and the values it takes.
struct SweepAxis {
  std::string name;
  std::vector<int> values;
};
// Parses "NAME=LO:HI[:STEP]", "NAME=A,B,C" or "NAME=V"; throws std::invalid_argument naming text.
SweepAxis parse_axis(const std::string& text);

struct SweepFile {
  std::vector<SweepAxis> axes;
  std::vector<int> axis_lines;  // the line of each axis
  std::string designs;          // the 'design' line's list; empty if there is none
  int design_line = 0;
};
// Parses a sweep file read from `in`; `name` is the file's name in messages,
// which all read "NAME:LINE: what is wrong". Throws std::invalid_argument.
SweepFile parse_sweep_file(std::istream& in, const std::string& name);

// Configurations of a product sweep: designs x the values of every axis,
// saturated at UINT64_MAX.
uint64_t sweep_size(size_t designs, const std::vector<SweepAxis>& axes);

}  // namespace cdsim
