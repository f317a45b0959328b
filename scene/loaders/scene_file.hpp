// Scene files and mesh files given with --scene (docs/scenes.md):
//   FILE.json                       a scene: mesh, camera, resolution, texture size
//   FILE.obj, FILE.gltf, FILE.glb   a mesh, with --camera
//   FILE.bsp, FILE.pk3:maps/X.bsp   a Quake 3 map, with --spawn N or --camera
// and the parsing of --camera and --resolution.
#pragma once

#include <optional>
#include <string>

#include "scene.hpp"

namespace cdsim {

inline constexpr int kDefaultWidth = 1920, kDefaultHeight = 1080;
// Texture size for materials whose image is unknown, unless a scene file says otherwise.
inline constexpr int kDefaultTextureSize = 256;

// The contents of a JSON scene file, validated; the mesh path is resolved
// relative to the scene file.
struct SceneFile {
  std::string mesh;
  std::optional<Camera> camera;
  std::optional<int> spawn;
  std::optional<glm::ivec2> resolution;
  std::optional<glm::ivec2> texture_size;
  // The normalised (s, t) of every mesh corner without a texture coordinate;
  // without it such a mesh is refused (docs/scenes.md).
  std::optional<glm::dvec2> missing_texcoord;
};

// The largest |s| or |t| of missing_texcoord: whole periods beyond it change
// nothing (the mesh builder shifts them away), and it keeps s times a texture
// size far inside a double's integers.
inline constexpr double kMaxMissingTexcoord = 1e6;

// Throws InputError naming `path` and the field for anything missing, of the
// wrong type, out of range or unknown.
SceneFile parse_scene_json(const std::string& text, const std::string& path);

// --camera "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_y[,near]"; without near, `default_near`.
Camera parse_camera_option(const std::string& text, double default_near);
// --resolution "WxH".
glm::ivec2 parse_resolution_option(const std::string& text);
// The --camera text that gives back `camera` exactly (with its near plane).
std::string camera_option_text(const Camera& camera);

// Refuses a camera that cannot make a view: non-finite values, eye at the
// target, up along the view direction, fov_y outside (0, 180), near <= 0.
void validate_camera(const Camera& camera, const std::string& where);

// True for the specs load_scene_file reads (by extension, ignoring case).
bool is_scene_file(const std::string& spec);

// Loads a scene or mesh file, or "default" with options, and projects it.
Scene load_scene_file(const std::string& spec, const SceneOptions& options);

}  // namespace cdsim
