#include "obj.hpp"

#include <fmt/format.h>

#include <functional>
#include <sstream>

#include "file_io.hpp"
#include "image_size.hpp"
#include "mesh_builder.hpp"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#endif
#include <tiny_obj_loader.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace cdsim {

namespace {

using ImageLookup = std::function<std::optional<glm::ivec2>(const std::string& texture_name)>;

LoadedObj load_obj_stream(std::istream& obj, tinyobj::MaterialReader& materials_reader,
                          const std::string& name, glm::ivec2 default_texture_size,
                          const ImageLookup& lookup) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &obj,
                                   &materials_reader, /*triangulate=*/false);
  while (!err.empty() && err.back() == '\n') err.pop_back();
  if (!ok) throw InputError(fmt::format("{}: not a readable OBJ file: {}", name, err));

  std::vector<glm::ivec2> material_size;
  size_t sized = 0;
  for (const tinyobj::material_t& m : materials) {
    std::optional<glm::ivec2> size;
    if (lookup && !m.diffuse_texname.empty()) size = lookup(m.diffuse_texname);
    sized += size.has_value();
    material_size.push_back(size.value_or(default_texture_size));
  }

  const size_t positions = attrib.vertices.size() / 3, texcoords = attrib.texcoords.size() / 2;
  MeshBuilder builder(name);
  size_t faces = 0, skipped = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t face = 0; face < mesh.num_face_vertices.size(); ++face) {
      const size_t corners = mesh.num_face_vertices[face];
      const auto where = [&] { return fmt::format("object '{}' face {}", shape.name, face); };
      if (offset + corners > mesh.indices.size())
        throw InputError(fmt::format("{}: {}: the face's {} corners run past the {} indices read "
                                     "(a face may have at most 255 corners)",
                                     name, where(), corners, mesh.indices.size()));
      ++faces;
      if (corners < 3) {
        ++skipped;
        offset += corners;
        continue;
      }
      glm::ivec2 texture = default_texture_size;
      if (face < mesh.material_ids.size()) {
        const int material = mesh.material_ids[face];
        if (material >= int(material_size.size()))
          throw InputError(fmt::format("{}: {}: material {} is outside the {} materials", name,
                                       where(), material, material_size.size()));
        if (material >= 0) texture = material_size[size_t(material)];
      }
      std::vector<MeshVertex> polygon;
      for (size_t k = 0; k < corners; ++k) {
        const tinyobj::index_t index = mesh.indices[offset + k];
        if (index.vertex_index < 0 || size_t(index.vertex_index) >= positions)
          throw InputError(fmt::format("{}: {}: corner {} refers to vertex {}, but the file has {} "
                                       "(v lines, counted from 1)",
                                       name, where(), k, index.vertex_index + 1, positions));
        if (index.texcoord_index >= 0 && size_t(index.texcoord_index) >= texcoords)
          throw InputError(fmt::format("{}: {}: corner {} refers to texture coordinate {}, but the "
                                       "file has {} (vt lines, counted from 1)",
                                       name, where(), k, index.texcoord_index + 1, texcoords));
        MeshVertex v;
        const size_t p = 3 * size_t(index.vertex_index);
        v.position = {attrib.vertices[p], attrib.vertices[p + 1], attrib.vertices[p + 2]};
        if (index.texcoord_index >= 0) {
          const size_t t = 2 * size_t(index.texcoord_index);
          // OBJ's t runs up the image; the unit's v runs down it, as in glTF.
          v.texcoord = {attrib.texcoords[t], 1.0 - double(attrib.texcoords[t + 1])};
        }
        polygon.push_back(v);
      }
      offset += corners;
      for (size_t k = 1; k + 1 < polygon.size(); ++k)
        builder.add(polygon[0], polygon[k], polygon[k + 1], texture, where);
    }
  }
  while (!warn.empty() && warn.back() == '\n') warn.pop_back();
  for (char& c : warn)
    if (c == '\n') c = ';';
  LoadedObj out;
  out.summary = fmt::format("{} faces, {} triangles, {} materials ({} with a known texture size)",
                            faces, builder.triangle_count(), materials.size(), sized);
  if (skipped) out.summary += fmt::format(", {} faces of fewer than 3 corners skipped", skipped);
  if (!warn.empty()) out.summary += "; tinyobjloader: " + warn;
  out.mesh = builder.take();
  return out;
}

}  // namespace

LoadedObj load_obj(const std::string& path, glm::ivec2 default_texture_size) {
  const std::vector<uint8_t> bytes = read_file_bytes(path);
  std::istringstream obj(std::string(bytes.begin(), bytes.end()));
  const std::string directory = directory_of(path);
  tinyobj::MaterialFileReader materials(directory);
  const ImageLookup lookup = [&](const std::string& texture) {
    return image_size_from_file(resolve_relative(path, texture));
  };
  return load_obj_stream(obj, materials, path, default_texture_size, lookup);
}

LoadedObj load_obj_from_memory(const std::string& obj_text, const std::string& mtl_text,
                               const std::string& name, glm::ivec2 default_texture_size) {
  std::istringstream obj(obj_text), mtl(mtl_text);
  tinyobj::MaterialStreamReader materials(mtl);
  return load_obj_stream(obj, materials, name, default_texture_size, {});
}

}  // namespace cdsim
