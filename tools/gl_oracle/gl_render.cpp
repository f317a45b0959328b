#include "gl_render.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace gl_oracle {

namespace {

// Every GL entry point beyond what EGL exports is fetched with eglGetProcAddress
// (EGL 1.5 returns core functions too), so the tool links only libEGL.
#define GL_ORACLE_FUNCTIONS(X)                                               \
  X(PFNGLGETSTRINGPROC, glGetString)                                         \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                     \
  X(PFNGLGETERRORPROC, glGetError)                                           \
  X(PFNGLGENTEXTURESPROC, glGenTextures)                                     \
  X(PFNGLBINDTEXTUREPROC, glBindTexture)                                     \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                                 \
  X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                                       \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                               \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                             \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                             \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)                   \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)               \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                       \
  X(PFNGLDRAWBUFFERSPROC, glDrawBuffers)                                     \
  X(PFNGLREADBUFFERPROC, glReadBuffer)                                       \
  X(PFNGLVIEWPORTPROC, glViewport)                                           \
  X(PFNGLSCISSORPROC, glScissor)                                             \
  X(PFNGLENABLEPROC, glEnable)                                               \
  X(PFNGLDISABLEPROC, glDisable)                                             \
  X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv)                                 \
  X(PFNGLCREATESHADERPROC, glCreateShader)                                   \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                                   \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)                                 \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                     \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                           \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                                   \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                 \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                                   \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                     \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                   \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                         \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                                       \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                                 \
  X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                             \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                             \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                       \
  X(PFNGLGENBUFFERSPROC, glGenBuffers)                                       \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                                       \
  X(PFNGLBUFFERDATAPROC, glBufferData)                                       \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                 \
  X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)                     \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray)             \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays)                                       \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                     \
  X(PFNGLREADPIXELSPROC, glReadPixels)                                       \
  X(PFNGLFINISHPROC, glFinish)

struct Gl {
#define GL_ORACLE_DECLARE(type, name) type name = nullptr;
  GL_ORACLE_FUNCTIONS(GL_ORACLE_DECLARE)
#undef GL_ORACLE_DECLARE
  PFNGLCLIPCONTROLPROC glClipControl = nullptr;  // GL 4.5 / ARB_clip_control; optional
};

// Smooth (perspective-correct) u, v: GL interpolates u/w and 1/w linearly in
// window space and divides, which is the exact reference's U/q. The id is flat.
const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec4 clip_position;
layout(location = 1) in vec2 texcoord;
layout(location = 2) in float triangle_id;
out vec2 uv;
flat out float id;
void main() {
  gl_Position = clip_position;
  uv = texcoord;
  id = triangle_id;
}
)";

const char* kFragmentShader = R"(#version 330 core
in vec2 uv;
flat in float id;
layout(location = 0) out vec4 colour;
void main() { colour = vec4(uv, id, 1.0); }
)";

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error " + std::to_string(e);
  }
}

}  // namespace

struct GlRenderer::State {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  Gl gl;
  GLuint texture = 0, framebuffer = 0, program = 0, vao = 0, vbo = 0;
};

GlRenderer::GlRenderer(int tile_width, int tile_height, bool clip_upper_left)
    : width_(tile_width), height_(tile_height), state_(new State) {
  // Mesa's software rasteriser, headless, with no on-disk shader cache.
  setenv("EGL_PLATFORM", "surfaceless", 1);
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
  State& s = *state_;
  try {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || !std::strstr(client, "EGL_MESA_platform_surfaceless"))
      throw Unavailable("EGL has no EGL_MESA_platform_surfaceless (is libegl-mesa0 installed?)");
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_platform_display) throw Unavailable("EGL has no eglGetPlatformDisplayEXT");
    s.display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (s.display == EGL_NO_DISPLAY) throw Unavailable("no EGL surfaceless display");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(s.display, &major, &minor))
      throw Unavailable("eglInitialize failed on the surfaceless platform: " +
                        egl_error_name(eglGetError()));
    const char* extensions = eglQueryString(s.display, EGL_EXTENSIONS);
    if (!extensions || !std::strstr(extensions, "EGL_KHR_surfaceless_context"))
      throw Unavailable("EGL display lacks EGL_KHR_surfaceless_context");
    if (!eglBindAPI(EGL_OPENGL_API)) throw Unavailable("eglBindAPI(EGL_OPENGL_API) failed");
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    const bool no_config = std::strstr(extensions, "EGL_KHR_no_config_context") != nullptr;
    if (!no_config && (!eglChooseConfig(s.display, config_attribs, &config, 1, &configs) || configs < 1))
      throw Unavailable("no EGL config renders OpenGL");
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    s.context = eglCreateContext(s.display, no_config ? EGL_NO_CONFIG_KHR : config,
                                 EGL_NO_CONTEXT, context_attribs);
    if (s.context == EGL_NO_CONTEXT)
      throw Unavailable("cannot create an OpenGL 3.3 core context: " +
                        egl_error_name(eglGetError()));
    if (!eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, s.context))
      throw Unavailable("eglMakeCurrent without a surface failed: " +
                        egl_error_name(eglGetError()));
#define GL_ORACLE_LOAD(type, name)                                                  \
  s.gl.name = reinterpret_cast<type>(eglGetProcAddress(#name));                     \
  if (!s.gl.name) throw Unavailable("OpenGL entry point " #name " is missing");
    GL_ORACLE_FUNCTIONS(GL_ORACLE_LOAD)
#undef GL_ORACLE_LOAD
    s.gl.glClipControl = reinterpret_cast<PFNGLCLIPCONTROLPROC>(eglGetProcAddress("glClipControl"));
    const Gl& gl = s.gl;
    renderer_ = reinterpret_cast<const char*>(gl.glGetString(GL_RENDERER));
    version_ = reinterpret_cast<const char*>(gl.glGetString(GL_VERSION));
    if (renderer_.find("llvmpipe") == std::string::npos)
      throw Unavailable("the OpenGL renderer is '" + renderer_ + "', not llvmpipe");
  } catch (...) {
    if (s.display != EGL_NO_DISPLAY) {
      eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (s.context != EGL_NO_CONTEXT) eglDestroyContext(s.display, s.context);
      eglTerminate(s.display);
    }
    delete state_;
    throw;
  }

  const Gl& gl = s.gl;
  GLint dims[2] = {0, 0}, bounds[2] = {0, 0};
  gl.glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
  gl.glGetIntegerv(GL_VIEWPORT_BOUNDS_RANGE, bounds);
  gl.glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &limits_.max_renderbuffer);
  limits_.max_dim = std::min(dims[0], dims[1]);
  limits_.bounds_lo = bounds[0];
  limits_.bounds_hi = bounds[1];
  if (gl.glGetError() != GL_NO_ERROR) {
    // GL_VIEWPORT_BOUNDS_RANGE needs GL 4.1 / ARB_viewport_array; assume the
    // minimum the specification allows for the viewport size we use.
    limits_.bounds_lo = -2 * limits_.max_dim;
    limits_.bounds_hi = 2 * limits_.max_dim - 1;
  }

  gl.glGenTextures(1, &s.texture);
  gl.glBindTexture(GL_TEXTURE_2D, s.texture);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width_, height_, 0, GL_RGBA, GL_FLOAT, nullptr);
  check("creating the RGBA32F colour buffer");
  gl.glGenFramebuffers(1, &s.framebuffer);
  gl.glBindFramebuffer(GL_FRAMEBUFFER, s.framebuffer);
  gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, s.texture, 0);
  const GLenum draw_buffer = GL_COLOR_ATTACHMENT0;
  gl.glDrawBuffers(1, &draw_buffer);
  gl.glReadBuffer(GL_COLOR_ATTACHMENT0);
  if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Unavailable("an RGBA32F framebuffer object is not complete on this renderer");

  const auto compile = [&](GLenum kind, const char* source) {
    const GLuint shader = gl.glCreateShader(kind);
    gl.glShaderSource(shader, 1, &source, nullptr);
    gl.glCompileShader(shader);
    GLint ok = 0;
    gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      gl.glGetShaderInfoLog(shader, sizeof log, nullptr, log);
      throw std::runtime_error(std::string("shader does not compile: ") + log);
    }
    return shader;
  };
  const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
  const GLuint fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  s.program = gl.glCreateProgram();
  gl.glAttachShader(s.program, vs);
  gl.glAttachShader(s.program, fs);
  gl.glLinkProgram(s.program);
  GLint linked = 0;
  gl.glGetProgramiv(s.program, GL_LINK_STATUS, &linked);
  if (!linked) {
    char log[4096] = {};
    gl.glGetProgramInfoLog(s.program, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("program does not link: ") + log);
  }
  gl.glDeleteShader(vs);
  gl.glDeleteShader(fs);
  gl.glUseProgram(s.program);

  gl.glGenVertexArrays(1, &s.vao);
  gl.glBindVertexArray(s.vao);
  gl.glGenBuffers(1, &s.vbo);
  gl.glBindBuffer(GL_ARRAY_BUFFER, s.vbo);
  const GLsizei stride = sizeof(GlVertex);
  gl.glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, stride,
                           reinterpret_cast<const void*>(offsetof(GlVertex, clip)));
  gl.glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride,
                           reinterpret_cast<const void*>(offsetof(GlVertex, u)));
  gl.glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride,
                           reinterpret_cast<const void*>(offsetof(GlVertex, id)));
  for (GLuint i = 0; i < 3; ++i) gl.glEnableVertexAttribArray(i);

  // Plain fixed-function state: no culling (both windings are drawn), no
  // depth, stencil, blending, scissor, dithering or multisampling.
  for (GLenum cap : {GL_CULL_FACE, GL_DEPTH_TEST, GL_STENCIL_TEST, GL_BLEND, GL_SCISSOR_TEST,
                     GL_DITHER, GL_MULTISAMPLE})
    gl.glDisable(cap);
  // Depth is not used: keep every triangle regardless of z (z is 0 anyway).
  gl.glEnable(GL_DEPTH_CLAMP);
  if (clip_upper_left) {
    if (!gl.glClipControl) throw std::runtime_error("glClipControl is not available");
    gl.glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  }
  gl.glPixelStorei(GL_PACK_ALIGNMENT, 4);
  check("setting up the pipeline");
}

GlRenderer::~GlRenderer() {
  State& s = *state_;
  const Gl& gl = s.gl;
  gl.glDeleteBuffers(1, &s.vbo);
  gl.glDeleteVertexArrays(1, &s.vao);
  gl.glDeleteProgram(s.program);
  gl.glDeleteFramebuffers(1, &s.framebuffer);
  gl.glDeleteTextures(1, &s.texture);
  eglMakeCurrent(s.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(s.display, s.context);
  eglTerminate(s.display);
  delete state_;
}

void GlRenderer::check(const char* what) {
  const GLenum e = state_->gl.glGetError();
  if (e != GL_NO_ERROR)
    throw std::runtime_error(std::string("OpenGL error 0x") + [&] {
      char b[16];
      std::snprintf(b, sizeof b, "%04x", e);
      return std::string(b);
    }() + " while " + what);
}

void GlRenderer::upload(const std::vector<GlVertex>& vertices) {
  state_->gl.glBufferData(GL_ARRAY_BUFFER,
                          static_cast<GLsizeiptr>(vertices.size() * sizeof(GlVertex)),
                          vertices.data(), GL_STATIC_DRAW);
  check("uploading vertices");
}

void GlRenderer::clear(int x, int y, int width, int height) {
  const Gl& gl = state_->gl;
  const GLfloat empty[4] = {0.0f, 0.0f, -1.0f, 0.0f};
  gl.glEnable(GL_SCISSOR_TEST);
  gl.glScissor(x, y, width, height);
  gl.glClearBufferfv(GL_COLOR, 0, empty);
  gl.glDisable(GL_SCISSOR_TEST);
}

void GlRenderer::draw(int64_t index, int x, int y, int size) {
  const Gl& gl = state_->gl;
  gl.glViewport(x, y, size, size);
  gl.glDrawArrays(GL_TRIANGLES, static_cast<GLint>(3 * index), 3);
}

void GlRenderer::read(int x, int y, int width, int height, std::vector<Texel>& out) {
  out.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  state_->gl.glReadPixels(x, y, width, height, GL_RGBA, GL_FLOAT, out.data());
  check("reading the colour buffer back");
}

}  // namespace gl_oracle
