// Wavefront OBJ with MTL materials. tinyobjloader reads the vertices and the
// materials; the faces are read here, with their line numbers, and fanned
// into triangles after their indices are checked (tinyobjloader's
// triangulation reads vertices before any check).
#pragma once

#include <optional>
#include <string>

#include "scene.hpp"

namespace cdsim {

struct LoadedObj {
  Mesh mesh;
  std::string summary;  // counts and warnings, for the scene description
};

// Texture sizes come from each material's map_Kd image header, resolved
// relative to the .obj file, else `default_texture_size`. A face corner
// without a texture coordinate is refused (naming the line) unless
// `missing_texcoord` gives the (s, t) to use, as the mesh stores it (t down).
LoadedObj load_obj(const std::string& path, glm::ivec2 default_texture_size,
                   const std::optional<glm::dvec2>& missing_texcoord = std::nullopt);

// In memory: `mtl_text` answers every mtllib; images are not looked up.
LoadedObj load_obj_from_memory(const std::string& obj_text, const std::string& mtl_text,
                               const std::string& name, glm::ivec2 default_texture_size,
                               const std::optional<glm::dvec2>& missing_texcoord = std::nullopt);

}  // namespace cdsim
