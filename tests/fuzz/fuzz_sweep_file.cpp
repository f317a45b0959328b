// libFuzzer target: sweep files (cdsim sweep --file, app/sweep_file.cpp).
// Malformed input must be refused with std::invalid_argument; what is
// accepted must hold only in-range values, each parameter once, and a line
// number per axis.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "design.hpp"
#include "sweep_file.hpp"
#include "widths.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  cdsim::SweepFile file;
  try {
    file = cdsim::parse_sweep_file(in, "fuzz.sweep");
  } catch (const std::invalid_argument& e) {
    if (std::string(e.what()).rfind("fuzz.sweep:", 0) != 0) std::abort();  // file:line in every message
    return 0;
  }
  if (file.axes.size() != file.axis_lines.size()) std::abort();
  std::set<std::string> names;
  cdsim::Widths probe;
  for (const cdsim::SweepAxis& axis : file.axes) {
    if (!names.insert(axis.name).second || axis.values.empty()) std::abort();
    for (int value : axis.values) cdsim::set_param(probe, axis.name, value);  // throws: a bug
  }
  const auto designs = cdsim::parse_design_list(file.designs);
  if (cdsim::sweep_size(designs.size(), file.axes) == 0) std::abort();
  return 0;
}
