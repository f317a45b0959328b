// libFuzzer target: screen-space triangle lists (.tri, load_triangle_stream),
// then the unit's input check and snapping (to_unit) on every triangle read.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "scene.hpp"
#include "widths.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const cdsim::Scene scene = cdsim::load_triangle_stream(in, "fuzz.tri");
    const cdsim::Widths widths;
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
      try {
        cdsim::to_unit(scene.triangles[i], widths, i);
      } catch (const cdsim::InputError&) {
      }
    }
  } catch (const cdsim::InputError&) {
  }
  return 0;
}
