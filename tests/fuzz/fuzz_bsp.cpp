// libFuzzer target: Quake 3 BSP images (load_bsp_from_memory), with every
// shader's texture size "known" so that the lookup path runs, and the spawn
// cameras built and checked.
#include <cstddef>
#include <cstdint>

#include "loaders/bsp.hpp"
#include "loaders/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const cdsim::BspMap map = cdsim::load_bsp_from_memory(
        data, size, "fuzz.bsp", {256, 256},
        [](const std::string& shader) -> std::optional<glm::ivec2> {
          if (shader.size() % 2) return glm::ivec2(64, 32);
          return std::nullopt;
        });
    for (const cdsim::BspSpawnPoint& spawn : map.spawns) {
      try {
        cdsim::validate_camera(cdsim::spawn_camera(spawn, 640, 480), "spawn");
      } catch (const cdsim::InputError&) {
      }
    }
  } catch (const cdsim::InputError&) {
  }
  return 0;
}
