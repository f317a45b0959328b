// libFuzzer target: glTF 2.0, JSON or binary (.glb), in memory
// (load_gltf_from_memory): data: URIs only, no file access.
#include <cstddef>
#include <cstdint>

#include "loaders/gltf.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    cdsim::load_gltf_from_memory(data, size, "fuzz.gltf", {256, 256});
  } catch (const cdsim::InputError&) {
  }
  return 0;
}
