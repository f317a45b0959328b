// Scene front end (SPEC §10): transform, homogeneous clipping, perspective
// divide, viewport, into the screen-space Scene the model draws
// (model/screen_scene.hpp). It models nothing else; snapping happens at the
// unit's input (triangle.hpp) because subpixel_bits is a width.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "screen_scene.hpp"
#include "triangle.hpp"

namespace cdsim {

struct Camera {
  glm::dvec3 eye{0, 0, 0};
  glm::dvec3 target{0, 0, -1};
  glm::dvec3 up{0, 1, 0};
  double fov_y_degrees = 60;
  double near_plane = 0.05;
};

struct MeshVertex {
  glm::dvec3 position{0};
  glm::dvec2 texcoord{0};  // normalised (s, t); may exceed [0, 1] when tiling
};

struct Mesh {
  std::vector<MeshVertex> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;
  std::vector<glm::ivec2> texture_size;  // per triangle, texels
};

// Guard band: clipping keeps x and y within this many half-viewports of the
// centre, so snapped coordinates stay inside 16.8 while every clipped edge lies
// outside the viewport (which keeps shared edges watertight on screen).
inline constexpr double kGuardBand = 3.0;

Scene project(const Mesh& mesh, const Camera& camera, int width, int height,
              const std::string& name);

// The embedded default scene: a textured corridor, 1920x1080, camera rolled and
// pitched so that both line orientations and a floor reaching the horizon appear.
Mesh default_mesh();
Camera default_camera();
Scene default_scene();

// The embedded dense scene (--scene dense): a UV sphere of 128 x 256
// segments (65,024 triangles) filling the middle of a 1280x720 view, front
// and back faces drawn, so that triangles cover a few pixels each: the hard
// case for the unit's throughput (issue "Throughput on dense meshes").
Scene dense_scene();

// A list of screen-space triangles that bypass the front end, one per line:
// "x y w u v" for each of the three vertices (15 numbers); '#' starts a comment;
// a line "resolution W H" sets the viewport. Every number must be the whole
// word, finite and within the range of a double; a UTF-8 byte-order mark at the
// start is ignored; the file must be a regular file of at most
// limits::kMaxFileBytes holding at most limits::kMaxTriangles triangles.
// Throws InputError naming file:line and the offending text (escaped).
Scene load_triangle_file(const std::string& path);

// The scene options every subcommand takes (docs/scenes.md). Empty or -1: not given.
struct SceneOptions {
  std::string camera;      // --camera "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_y[,near]"
  int spawn = -1;          // --spawn N: the Nth spawn point of a Quake 3 map
  std::string resolution;  // --resolution WxH
  bool empty() const { return camera.empty() && spawn < 0 && resolution.empty(); }
};

// As load_triangle_file, from a stream or from text; `path` names it in messages.
Scene load_triangle_stream(std::istream& in, const std::string& path);
Scene load_triangle_text(std::string_view text, const std::string& path);

// "default", "hard:NAME", a .tri path, or a scene or mesh file
// (scene/loaders/scene_file.hpp): .json, .obj, .gltf, .glb, .bsp,
// FILE.pk3:maps/NAME.bsp. A scene without a single triangle to draw (an empty
// file or mesh, or a camera that sees none of the mesh) is refused with an
// InputError that says why (docs/scenes.md, "No triangle to draw").
Scene load_scene(const std::string& spec, const SceneOptions& options);
Scene load_scene(const std::string& spec);

}  // namespace cdsim
