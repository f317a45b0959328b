// Build-time generator of the RTL's parameter header: writes cd_widths.svh for
// one width configuration (widths.def with NAME=VALUE overrides), the same text
// as `cdsim widths --sv`; with --adaptive-leaf, that of the adaptive design's
// leaf unit (rtl/adaptive_unit.sv). The build runs it before Verilator sees
// the RTL.
#include <fmt/format.h>

#include <fstream>
#include <iostream>
#include <sstream>

#include "derived_widths.hpp"
#include "widths.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: cdsim_widths_header OUT.svh CONFIG [--adaptive-leaf] [NAME=VALUE...]\n";
    return 2;
  }
  try {
    cdsim::Widths widths;
    bool leaf = false;
    for (int i = 3; i < argc; ++i) {
      if (std::string(argv[i]) == "--adaptive-leaf") leaf = true;
      else cdsim::apply_setting(widths, argv[i]);
    }
    cdsim::validate(widths);
    const std::string text = leaf ? cdsim::rtl_header(cdsim::adaptive_leaf_widths(widths),
                                                      std::string(argv[2]) + ", adaptive leaf unit")
                                  : cdsim::rtl_header(widths, argv[2]);
    // Rewrite only on change, so that Verilator reruns only when a width changed.
    std::ifstream old(argv[1]);
    std::stringstream existing;
    existing << old.rdbuf();
    if (old && existing.str() == text) return 0;
    old.close();
    std::ofstream out(argv[1]);
    out << text;
    out.close();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write", argv[1]));
  } catch (const std::exception& e) {
    std::cerr << "cdsim_widths_header: " << argv[2] << ": " << e.what() << '\n';
    return 1;
  }
  return 0;
}
