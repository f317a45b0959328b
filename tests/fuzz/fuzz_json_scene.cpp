// libFuzzer target: JSON scene files (parse_scene_json), and the same bytes as
// the --camera and --resolution option texts.
#include <cstddef>
#include <cstdint>
#include <string>

#include "loaders/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    cdsim::parse_scene_json(text, "dir/fuzz.json");
  } catch (const cdsim::InputError&) {
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
