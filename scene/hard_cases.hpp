// The named hard cases of SPEC §9, as scenes: `--scene hard:NAME`, and
// `--scene hard:all` for all of them in one 8192 x 8192 scene. Each case's
// expected behaviour is written beside it (hard_cases.cpp) and asserted for
// every design in tests/hard_cases_test.cpp; docs/hard_cases.md lists them.
#pragma once

#include <string>
#include <vector>

#include "scene.hpp"

namespace cdsim {

struct HardCase {
  std::string name;
  std::string expected;  // the behaviour the tests assert
};

const std::vector<HardCase>& hard_cases();

// "hard:NAME" or "hard:all". Throws InputError for an unknown name, and for
// hard:bad-input (whose triangles the unit must refuse) when it is converted
// for the unit, not here.
bool is_hard_case(const std::string& spec);
Scene hard_case_scene(const std::string& spec);

}  // namespace cdsim
