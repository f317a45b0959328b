// Collects the triangles a loader finds into a cdsim::Mesh, refusing
// non-finite values and values beyond limits::kMaxMeshCoordinate, and
// enforcing limits::kMaxTriangles.
#pragma once

#include <functional>
#include <string>

#include "scene.hpp"

namespace cdsim {

class MeshBuilder {
 public:
  // `source` names the file in messages.
  explicit MeshBuilder(std::string source) : source_(std::move(source)) {}

  // Adds one triangle with its own three vertices. Texture coordinates are
  // shifted by whole periods so that the smallest s and t of the triangle lie
  // in [0, 1): invisible under repeat wrapping, and it keeps |u| and |v| in
  // texels far below the unit's 2^15 limit on large tiled surfaces.
  // `where` names the triangle for an error message (called only on error).
  void add(MeshVertex a, MeshVertex b, MeshVertex c, glm::ivec2 texture_size,
           const std::function<std::string()>& where);

  size_t triangle_count() const { return mesh_.triangles.size(); }
  Mesh take() { return std::move(mesh_); }

 private:
  std::string source_;
  Mesh mesh_;
};

}  // namespace cdsim
