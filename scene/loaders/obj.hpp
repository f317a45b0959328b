// Wavefront OBJ with MTL materials, read with tinyobjloader. Polygons are
// fanned into triangles here (after their indices are checked), not by
// tinyobjloader, whose triangulation reads vertices before any check.
#pragma once

#include <string>

#include "scene.hpp"

namespace cdsim {

struct LoadedObj {
  Mesh mesh;
  std::string summary;  // counts and warnings, for the scene description
};

// Texture sizes come from each material's map_Kd image header, resolved
// relative to the .obj file, else `default_texture_size`.
LoadedObj load_obj(const std::string& path, glm::ivec2 default_texture_size);

// In memory: `mtl_text` answers every mtllib; images are not looked up.
LoadedObj load_obj_from_memory(const std::string& obj_text, const std::string& mtl_text,
                               const std::string& name, glm::ivec2 default_texture_size);

}  // namespace cdsim
