// The implementations of the header-only loaders Debian ships as headers
// (libtinyobjloader-dev, libtinygltf-dev), compiled here so that sanitizer and
// fuzzer builds instrument them too. Compiled without our warnings.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

// Images are measured from their headers only (image_size.cpp); tinygltf never
// decodes or writes one.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
