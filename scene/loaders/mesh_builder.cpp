#include "mesh_builder.hpp"

#include <fmt/format.h>

#include <cmath>

#include "limits.hpp"

namespace cdsim {

void MeshBuilder::add(MeshVertex a, MeshVertex b, MeshVertex c, glm::ivec2 texture_size,
                      const std::function<std::string()>& where) {
  std::array<MeshVertex*, 3> corner{&a, &b, &c};
  for (size_t i = 0; i < 3; ++i) {
    const MeshVertex& m = *corner[i];
    if (!std::isfinite(m.position.x) || !std::isfinite(m.position.y) ||
        !std::isfinite(m.position.z))
      throw InputError(fmt::format("{}: {}: vertex {} position ({}, {}, {}) is not finite",
                                   source_, where(), i, m.position.x, m.position.y,
                                   m.position.z));
    if (!std::isfinite(m.texcoord.x) || !std::isfinite(m.texcoord.y))
      throw InputError(fmt::format("{}: {}: vertex {} texture coordinate ({}, {}) is not finite",
                                   source_, where(), i, m.texcoord.x, m.texcoord.y));
    const double limit = limits::kMaxMeshCoordinate;
    if (std::fabs(m.position.x) > limit || std::fabs(m.position.y) > limit ||
        std::fabs(m.position.z) > limit)
      throw InputError(fmt::format("{}: {}: vertex {} position ({}, {}, {}) is outside +-{:g}, the "
                                   "range of a float",
                                   source_, where(), i, m.position.x, m.position.y, m.position.z,
                                   limit));
    if (std::fabs(m.texcoord.x) > limit || std::fabs(m.texcoord.y) > limit)
      throw InputError(fmt::format("{}: {}: vertex {} texture coordinate ({}, {}) is outside "
                                   "+-{:g}, the range of a float",
                                   source_, where(), i, m.texcoord.x, m.texcoord.y, limit));
  }
  if (texture_size.x < 1 || texture_size.y < 1 || texture_size.x > limits::kMaxTextureSize ||
      texture_size.y > limits::kMaxTextureSize)
    throw InputError(fmt::format("{}: {}: texture size {}x{} is outside 1..{}", source_, where(),
                                 texture_size.x, texture_size.y, limits::kMaxTextureSize));
  if (mesh_.triangles.size() >= limits::kMaxTriangles)
    throw InputError(fmt::format("{}: more than {} triangles, the cap on one mesh", source_,
                                 limits::kMaxTriangles));
  const double shift_s = std::floor(std::min({a.texcoord.x, b.texcoord.x, c.texcoord.x}));
  const double shift_t = std::floor(std::min({a.texcoord.y, b.texcoord.y, c.texcoord.y}));
  const auto base = static_cast<uint32_t>(mesh_.vertices.size());
  for (MeshVertex* m : corner) {
    m->texcoord -= glm::dvec2(shift_s, shift_t);
    mesh_.vertices.push_back(*m);
  }
  mesh_.triangles.push_back({base, base + 1, base + 2});
  mesh_.texture_size.push_back(texture_size);
}

}  // namespace cdsim
