// Texture sizes from image headers only (stb_image's stbi_info): PNG, JPEG,
// TGA, BMP, GIF, PSD, HDR, PNM. The pixels are never decoded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include <glm/glm.hpp>

namespace cdsim {

// The size in texels, or nothing when the header is not a recognised image.
// Throws InputError (naming `name`) for a size outside 1..limits::kMaxTextureSize.
std::optional<glm::ivec2> image_size_from_memory(const uint8_t* data, size_t size,
                                                 const std::string& name);

// As above for a file; nothing when it is not a regular file, cannot be
// opened or is not recognised.
std::optional<glm::ivec2> image_size_from_file(const std::string& path);

}  // namespace cdsim
