// glTF 2.0 (.gltf with its buffers, or .glb), read with tinygltf. The default
// scene's node hierarchy is followed with each node's transform; triangle
// lists, strips and fans are drawn with TEXCOORD_n of the base colour texture.
// Images are never decoded: only their headers are read for the texture size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "scene.hpp"

namespace cdsim {

struct LoadedGltf {
  Mesh mesh;
  std::string summary;  // counts, for the scene description
};

// .gltf or .glb (told apart by the 'glTF' magic, not by the name). A
// primitive without the TEXCOORD_n its material reads (TEXCOORD_0 without a
// texture) is refused unless `missing_texcoord` gives the (s, t) to use.
LoadedGltf load_gltf(const std::string& path, glm::ivec2 default_texture_size,
                     const std::optional<glm::dvec2>& missing_texcoord = std::nullopt);

// In memory: only data: URIs and .glb's binary chunk are available; a
// reference to an external file is refused.
LoadedGltf load_gltf_from_memory(const uint8_t* data, size_t size, const std::string& name,
                                 glm::ivec2 default_texture_size,
                                 const std::optional<glm::dvec2>& missing_texcoord = std::nullopt);

}  // namespace cdsim
