// libFuzzer target: OBJ text (load_obj_from_memory). The input is split at the
// first line "#mtl": what comes before is the .obj, what follows answers
// every mtllib.
#include <cstddef>
#include <cstdint>
#include <string>

#include "loaders/obj.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const auto split = input.find("\n#mtl\n");
  const std::string obj = input.substr(0, split);
  const std::string mtl = split == std::string::npos ? std::string() : input.substr(split + 6);
  try {
    cdsim::load_obj_from_memory(obj, mtl, "fuzz.obj", {256, 256});
  } catch (const cdsim::InputError&) {
  }
  return 0;
}
