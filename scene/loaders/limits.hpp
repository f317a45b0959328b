// Caps that keep a hostile or broken input file from exhausting memory or
// time. A file that exceeds one is refused with an InputError that names the
// cap, never truncated silently.
#pragma once

#include <cstddef>
#include <cstdint>

namespace cdsim::limits {

// Largest file (or archive entry) read into memory. The largest OpenArena map
// is 7.6 MB; glTF buffers of real scenes stay far below this.
inline constexpr uint64_t kMaxFileBytes = uint64_t{256} << 20;

// Largest mesh handed to the front end, in triangles (after patch tessellation
// and glTF instancing): about 600 MB of mesh. The largest OpenArena map makes
// a few hundred thousand.
inline constexpr size_t kMaxTriangles = size_t{1} << 22;

// Largest texture, in texels per side (SPEC §9: textures up to 16384 texels).
inline constexpr int kMaxTextureSize = 16384;

// Largest viewport, in pixels per side (SPEC §1).
inline constexpr int kMaxResolution = 8192;

// Deepest glTF node hierarchy followed (a cyclic hierarchy is refused).
inline constexpr int kMaxNodeDepth = 64;

// Deepest nesting of arrays and objects in a JSON input (glTF, scene files),
// checked before parsing (json_structure.hpp). Real files nest a dozen levels
// (a glTF's extras and extensions included); the recursion that follows the
// parse (tinygltf's conversion of extras, nlohmann's dump) overflows an 8 MiB
// stack near 20,000 levels, and a sanitizer build far sooner.
inline constexpr int kMaxJsonDepth = 512;

// Largest magnitude of a mesh coordinate after every transform: the largest
// float, the widest any of the formats stores a position in. A glTF node
// transform that goes beyond it has overflowed, and the front end's products
// (view, projection, clipping) stay finite in double precision below it.
inline constexpr double kMaxMeshCoordinate = 3.4028234663852886e38;  // FLT_MAX

// Largest magnitude of a camera's eye, target and up coordinates and of its
// near plane (the far plane is 10^6 near planes): beyond it the view and
// projection matrices lose every digit of a mesh of any real size.
inline constexpr double kMaxCameraCoordinate = 1e12;

// Smallest vertical field of view, in degrees. The front end clips in double
// precision, and a clipped vertex carries a rounding error of about 2^-52 of
// the distance, in half-viewports, of the edge's far end from the view axis:
// tan(angle off axis) / tan(fov_y / 2). At 1e-6 degrees a vertex 45 degrees
// off axis is 1.1e8 half-viewports away, an error of 1e-4 pixel at 8192
// pixels, a fortieth of a subpixel; at 1e-10 degrees the error is a pixel, and
// at 1e-15 degrees a screen-filling quad draws half the screen (docs/scenes.md,
// "Camera range"). Any fov_y below 180 degrees keeps coverage exact.
inline constexpr double kMinFovDegrees = 1e-6;

// Smallest near plane. A triangle clipped at the near plane gets w = near,
// and the unit's input needs 1/w to be a normal float (model/triangle.cpp):
// 1/w breaks past the largest float below near = 2.9e-39; 1e-36 leaves the
// clipping's rounding a factor of 1000.
inline constexpr double kMinNearPlane = 1e-36;

}  // namespace cdsim::limits
