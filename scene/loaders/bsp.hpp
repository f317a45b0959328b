// Quake 3 BSP (IBSP version 46) maps, read by our own reader: the entities,
// shaders, vertices, mesh vertices and faces lumps. Polygons (face type 1) and
// triangle meshes (type 3) are taken as they are; Bézier patches (type 2) are
// grids of 3x3-control-point biquadratic patches, each tessellated into a
// fixed kPatchTessellationLevel x kPatchTessellationLevel grid of quads;
// billboards (type 4) and faces whose shader has SURF_NODRAW are skipped.
//
// Coordinates stay in Quake units and Quake's z-up frame: a spawn camera has
// up = +z, and a --camera for a map is given in the map's own coordinates.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "scene.hpp"

namespace cdsim {

inline constexpr int kPatchTessellationLevel = 8;

// Quake 3 puts a spawning player 9 units above the spawn entity's origin and
// the eye DEFAULT_VIEWHEIGHT = 26 units above that.
inline constexpr double kSpawnLift = 9.0;
inline constexpr double kViewHeight = 26.0;
// Quake 3's default field of view is 90 degrees horizontally (cg_fov 90).
inline constexpr double kSpawnHorizontalFov = 90.0;
// Quake 3's near plane (r_znear 4), in Quake units.
inline constexpr double kSpawnNearPlane = 4.0;

struct BspSpawnPoint {
  std::string classname;  // info_player_deathmatch or info_player_start
  int entity = 0;         // index in the entities lump
  glm::dvec3 origin{0};
  double yaw_degrees = 0;    // "angle", or the second of "angles"
  double pitch_degrees = 0;  // the first of "angles"; positive looks down
};

struct BspStats {
  size_t faces = 0, polygons = 0, meshes = 0, patches = 0, billboards = 0, nodraw = 0;
  size_t shaders = 0, shaders_sized = 0;  // shaders used by drawn faces, and how many have a size
};

struct BspMap {
  Mesh mesh;
  std::vector<BspSpawnPoint> spawns;
  BspStats stats;
};

// Size of the image of a shader ("textures/base_wall/concrete"), when known.
using TextureSizeLookup = std::function<std::optional<glm::ivec2>(const std::string& shader)>;

// Parses a whole .bsp image; `name` is used in messages. Every offset, count
// and index is checked; bad input throws InputError naming the lump, record
// and byte offset.
BspMap load_bsp_from_memory(const uint8_t* data, size_t size, const std::string& name,
                            glm::ivec2 default_texture_size, const TextureSizeLookup& lookup = {});

// A .bsp file, or "FILE.pk3:maps/NAME.bsp". Texture sizes come from the
// shader name's .tga, .jpg or .png in the same archive (for a loose file, in
// the directory above maps/), else `default_texture_size`.
BspMap load_bsp(const std::string& spec, glm::ivec2 default_texture_size);

class Pk3Archive;
// A map inside an open archive, with texture sizes from the same archive.
BspMap load_bsp_from_archive(const Pk3Archive& archive, const std::string& entry,
                             glm::ivec2 default_texture_size);

// Quake 3's entity text: a list of { "key" "value" ... } blocks. Throws
// InputError naming the byte offset of a syntax error.
std::vector<std::vector<std::pair<std::string, std::string>>> parse_entities(
    const std::string& text, const std::string& name);

// The camera a player would see through on spawning at `spawn`.
Camera spawn_camera(const BspSpawnPoint& spawn, int width, int height);

}  // namespace cdsim
