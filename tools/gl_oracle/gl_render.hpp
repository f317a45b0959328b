// A headless OpenGL 3.3 core context on Mesa's llvmpipe (EGL, surfaceless
// platform) and the few draw and read-back operations the oracle needs. Nothing
// here knows about cdsim: it draws clip-space triangles with a perspective-
// interpolated (u, v) varying and a flat per-triangle id into an RGBA32F
// colour buffer and reads it back.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace gl_oracle {

// Thrown when no EGL surfaceless llvmpipe context can be had: the oracle then
// skips instead of failing.
struct Unavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One vertex as GL receives it: clip-space position (x_ndc*w, y_ndc*w, 0, w),
// texture coordinates, and the triangle's id within its batch (flat).
struct GlVertex {
  float clip[4];
  float u, v;
  float id;
};

// One texel of the read-back colour buffer: (u, v, id, covered).
struct Texel {
  float u, v, id, covered;
};

struct ViewportLimits {
  int max_dim = 0;             // GL_MAX_VIEWPORT_DIMS (the smaller of the two)
  int bounds_lo = 0, bounds_hi = 0;  // GL_VIEWPORT_BOUNDS_RANGE
  int max_renderbuffer = 0;    // GL_MAX_RENDERBUFFER_SIZE
};

class GlRenderer {
 public:
  // Creates the context (throws Unavailable) and an RGBA32F framebuffer of
  // tile_width x tile_height. clip_upper_left selects glClipControl's
  // GL_UPPER_LEFT origin (an experiment switch; the oracle uses lower-left).
  GlRenderer(int tile_width, int tile_height, bool clip_upper_left);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  std::string renderer() const { return renderer_; }
  std::string version() const { return version_; }
  const ViewportLimits& limits() const { return limits_; }

  // Uploads every vertex once; draw() refers to triangles by index into it.
  void upload(const std::vector<GlVertex>& vertices);
  // Clears a window rectangle of the colour buffer to (0, 0, -1, 0).
  void clear(int x, int y, int width, int height);
  // Draws triangle `index` (vertices 3*index .. 3*index+2) through the viewport
  // whose lower-left corner is (x, y) in window pixels and whose size is size x size.
  void draw(int64_t index, int x, int y, int size);
  // Reads a window rectangle of the colour buffer, bottom row (smallest window y) first.
  void read(int x, int y, int width, int height, std::vector<Texel>& out);

 private:
  void check(const char* what);
  int width_, height_;
  std::string renderer_, version_;
  ViewportLimits limits_;
  struct State;
  State* state_;
};

}  // namespace gl_oracle
