#include "image_size.hpp"

#include <fmt/format.h>

#include <climits>
#include <filesystem>

#include "limits.hpp"
#include "triangle.hpp"

// Only the header parsers are used; STB_IMAGE_STATIC keeps every stb symbol in
// this translation unit so that nothing else can clash with it.
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wpedantic"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_FAILURE_STRINGS
#include <stb/stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace cdsim {

namespace {

std::optional<glm::ivec2> checked(int ok, int width, int height, const std::string& name) {
  if (!ok) return std::nullopt;
  if (width < 1 || height < 1 || width > limits::kMaxTextureSize ||
      height > limits::kMaxTextureSize)
    throw InputError(fmt::format("{}: image header says {}x{} texels; textures are limited to "
                                 "1..{} texels per side",
                                 name, width, height, limits::kMaxTextureSize));
  return glm::ivec2(width, height);
}

}  // namespace

std::optional<glm::ivec2> image_size_from_memory(const uint8_t* data, size_t size,
                                                 const std::string& name) {
  if (data == nullptr || size == 0 || size > static_cast<size_t>(INT_MAX)) return std::nullopt;
  int width = 0, height = 0, components = 0;
  const int ok = stbi_info_from_memory(data, static_cast<int>(size), &width, &height, &components);
  return checked(ok, width, height, name);
}

std::optional<glm::ivec2> image_size_from_file(const std::string& path) {
  // A directory, device or FIFO is no image (and a FIFO would block the read).
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return std::nullopt;
  int width = 0, height = 0, components = 0;
  const int ok = stbi_info(path.c_str(), &width, &height, &components);
  return checked(ok, width, height, path);
}

}  // namespace cdsim
