// libFuzzer target: JSON scene files (parse_scene_json), and the same bytes as
// the --camera and --resolution option texts. The structure checks every JSON
// reader runs first (json_structure.hpp) get the bytes too: they must refuse
// only with InputError, and a scene file that parses must be within the
// depth cap and hold no repeated key, since those are checked before it is read.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "loaders/json_structure.hpp"
#include "loaders/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  bool parsed = false;
  try {
    cdsim::parse_scene_json(text, "dir/fuzz.json");
    parsed = true;
  } catch (const cdsim::InputError&) {
  }
  // A small cap as well, so that short inputs reach the refusal too.
  for (const int cap : {2, cdsim::limits::kMaxJsonDepth}) {
    try {
      cdsim::check_json_depth(text, "fuzz.json", cap);
    } catch (const cdsim::InputError&) {
      if (parsed && cap == cdsim::limits::kMaxJsonDepth) std::abort();  // read past the cap
    }
  }
  if (parsed) {
    try {
      cdsim::check_json_unique_keys(text, "fuzz.json");
    } catch (const cdsim::InputError&) {
      std::abort();  // a repeated key was read
    }
  }
  try {
    cdsim::parse_camera_option(text, 0.05);
  } catch (const cdsim::InputError&) {
  }
  try {
    cdsim::parse_resolution_option(text);
  } catch (const cdsim::InputError&) {
  }
  return 0;
}
