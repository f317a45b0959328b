#include "gltf.hpp"

#include <fmt/format.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <functional>
#include <filesystem>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "file_io.hpp"
#include "image_size.hpp"
#include "json_structure.hpp"
#include "limits.hpp"
#include "mesh_builder.hpp"
#include "strict_text.hpp"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#endif
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#include <tiny_gltf.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace cdsim {

namespace {

// Image sizes recorded by the image callback, by image index.
struct ImageSizes {
  std::string name;
  std::vector<std::optional<glm::ivec2>> size;
  std::string error;  // the first InputError from an image header
};

bool record_image_size(tinygltf::Image* image, const int image_index, std::string*, std::string*,
                       int, int, const unsigned char* bytes, int size, void* user) {
  auto& sizes = *static_cast<ImageSizes*>(user);
  if (image_index < 0) return true;
  if (sizes.size.size() <= size_t(image_index)) sizes.size.resize(size_t(image_index) + 1);
  // tinygltf hands over bufferView images without checking the view against its
  // buffer; those are measured after loading, with the bounds checked.
  if (image->bufferView >= 0 || bytes == nullptr || size <= 0) return true;
  try {
    sizes.size[size_t(image_index)] = image_size_from_memory(
        bytes, size_t(size), fmt::format("{}: image {}", sizes.name, image_index));
  } catch (const InputError& e) {
    if (sizes.error.empty()) sizes.error = e.what();
  }
  return true;
}

// Refuses every file access: an in-memory glTF has nothing beside it.
bool no_file_exists(const std::string&, void*) { return false; }
std::string no_expand(const std::string& path, void*) { return path; }
bool no_read(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
  if (err) *err += fmt::format("'{}' is an external file, not available in memory\n", path);
  return false;
}
bool no_write(std::string*, const std::string&, const std::vector<unsigned char>&, void*) {
  return false;
}

// Files beside a .gltf (buffers, images) through read_file_bytes: regular
// files only, within the size cap; the reason reaches tinygltf's message.
bool file_exists(const std::string& path, void*) {
  std::error_code error;
  return std::filesystem::exists(path, error);
}
bool read_capped(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  try {
    *out = read_file_bytes(path);
    return true;
  } catch (const InputError& e) {
    if (err) *err += std::string(e.what()) + "\n";
    return false;
  }
}

// Extensions a file may require that change nothing cdsim reads: materials'
// shading and lights. Any other (Draco or meshopt compression, quantised
// attributes, texture transforms, other image formats) changes the geometry,
// the texture coordinates or the texture, so a file requiring it is refused.
// How far a node's rotation may be from unit length: a quaternion written as
// floats with 4 significant digits is within 1e-3.
constexpr double kQuaternionTolerance = 1e-3;

bool supported_required_extension(const std::string& name) {
  return name.rfind("KHR_materials_", 0) == 0 || name == "KHR_lights_punctual";
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const ImageSizes& images, std::string name,
             glm::ivec2 default_texture, std::optional<glm::dvec2> missing_texcoord)
      : model_(model), images_(images), name_(std::move(name)),
        default_texture_(default_texture), missing_texcoord_(missing_texcoord), builder_(name_) {}

  LoadedGltf read();

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: {}", name_, what));
  }

  // A checked view of one accessor: element i, component c, as a double.
  // Sparse accessors are applied once and read from `values`.
  struct View {
    const uint8_t* base = nullptr;
    size_t stride = 0, count = 0;
    int component_type = 0, components = 0;
    bool normalized = false;
    std::vector<double> values;  // count * components, when not empty
    bool present() const { return base != nullptr || !values.empty(); }
    double get(size_t i, int c) const;
    double raw(size_t i, int c) const;
  };
  using Complaint = std::function<void(const std::string&)>;
  // The first byte of `count` elements of `element` bytes every `stride`
  // bytes from `byte_offset` in buffer view `buffer_view`, all within it.
  const uint8_t* checked_bytes(int buffer_view, size_t byte_offset, size_t count, size_t element,
                               size_t stride, const char* role, const Complaint& bad) const;
  void apply_sparse(const tinygltf::Accessor& a, View& out, const Complaint& bad) const;
  View accessor(int index, const std::string& what, std::initializer_list<int> types,
                std::initializer_list<int> component_types) const;
  glm::ivec2 texture_size(int material, int* texcoord_set);
  void visit(int node, const glm::dmat4& parent, int depth);
  // `node`: the node that instances the mesh, for messages; -1 for none.
  void add_mesh(int mesh, const glm::dmat4& transform, int node);

  const tinygltf::Model& model_;
  const ImageSizes& images_;
  std::string name_;
  glm::ivec2 default_texture_;
  std::optional<glm::dvec2> missing_texcoord_;
  MeshBuilder builder_;
  std::vector<bool> on_path_;
  size_t node_visits_ = 0, primitives_ = 0, skipped_primitives_ = 0, sized_primitives_ = 0,
         defaulted_primitives_ = 0;
};

double GltfReader::View::get(size_t i, int c) const {
  if (!values.empty()) return values[i * size_t(components) + size_t(c)];
  return raw(i, c);
}

double GltfReader::View::raw(size_t i, int c) const {
  const uint8_t* p = base + i * stride;
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p + 4 * c, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = p[c];
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p + 2 * c, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p + 4 * c, 4);
      return v;
    }
    default:
      return 0;
  }
}

const uint8_t* GltfReader::checked_bytes(int buffer_view, size_t byte_offset, size_t count,
                                         size_t element, size_t stride, const char* role,
                                         const Complaint& bad) const {
  if (buffer_view < 0 || size_t(buffer_view) >= model_.bufferViews.size())
    bad(fmt::format("{}buffer view {} is outside the {} buffer views", role, buffer_view,
                    model_.bufferViews.size()));
  const tinygltf::BufferView& view = model_.bufferViews[size_t(buffer_view)];
  if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
    bad(fmt::format("{}buffer view {} refers to buffer {}, outside the {} buffers", role,
                    buffer_view, view.buffer, model_.buffers.size()));
  const tinygltf::Buffer& buffer = model_.buffers[size_t(view.buffer)];
  if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
    bad(fmt::format("{}buffer view {} (bytes {}..+{}) lies outside buffer {} of {} bytes", role,
                    buffer_view, view.byteOffset, view.byteLength, view.buffer,
                    buffer.data.size()));
  if (count == 0) return nullptr;
  // The last element must end inside the view; checked without overflow.
  if (byte_offset > view.byteLength || (count - 1) > (view.byteLength - byte_offset) / stride ||
      element > view.byteLength - byte_offset - (count - 1) * stride)
    bad(fmt::format("{}{} elements of {} bytes every {} bytes from byte {} overrun buffer view {} "
                    "of {} bytes",
                    role, count, element, stride, byte_offset, buffer_view, view.byteLength));
  return buffer.data.data() + view.byteOffset + byte_offset;
}

GltfReader::View GltfReader::accessor(int index, const std::string& what,
                                      std::initializer_list<int> types,
                                      std::initializer_list<int> component_types) const {
  const Complaint bad = [&](const std::string& why) {
    fail(fmt::format("{}: accessor {}: {}", what, index, why));
  };
  if (index < 0 || size_t(index) >= model_.accessors.size())
    bad(fmt::format("outside the {} accessors", model_.accessors.size()));
  const tinygltf::Accessor& a = model_.accessors[size_t(index)];
  if (std::find(types.begin(), types.end(), a.type) == types.end())
    bad(fmt::format("type {} is not the expected one", a.type));
  if (std::find(component_types.begin(), component_types.end(), a.componentType) ==
      component_types.end())
    bad(fmt::format("component type {} is not supported here", a.componentType));
  const int component_bytes = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
  const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
  View out;
  out.count = a.count;
  out.component_type = a.componentType;
  out.components = components;
  out.normalized = a.normalized;
  const size_t element = size_t(component_bytes) * size_t(components);
  // A sparse accessor may leave out its buffer view: its base values are then zeros.
  if (a.bufferView >= 0 || !a.sparse.isSparse) {
    if (a.bufferView < 0 || size_t(a.bufferView) >= model_.bufferViews.size())
      bad(fmt::format("buffer view {} is outside the {} buffer views", a.bufferView,
                      model_.bufferViews.size()));
    const int stride = a.ByteStride(model_.bufferViews[size_t(a.bufferView)]);
    if (component_bytes <= 0 || components <= 0 || stride <= 0)
      bad(fmt::format("invalid byte stride {} for its type",
                      model_.bufferViews[size_t(a.bufferView)].byteStride));
    out.stride = size_t(stride);
    out.base = checked_bytes(a.bufferView, a.byteOffset, a.count, element, out.stride, "", bad);
  } else {
    out.stride = element;
  }
  if (a.sparse.isSparse) apply_sparse(a, out, bad);
  return out;
}

// glTF 2.0 §3.6.2.3: the accessor's values (or zeros), with `sparse.count`
// of them replaced: indices strictly increasing, each below the count.
void GltfReader::apply_sparse(const tinygltf::Accessor& a, View& out, const Complaint& bad) const {
  // Expanded in memory, so capped: three vertices a triangle of the largest mesh.
  const size_t max_elements = 3 * limits::kMaxTriangles;
  if (a.count > max_elements)
    bad(fmt::format("a sparse accessor of {} elements; cdsim expands at most {}", a.count,
                    max_elements));
  const auto& sparse = a.sparse;
  if (sparse.count < 1 || size_t(sparse.count) > a.count)
    bad(fmt::format("sparse.count {} is outside 1..{} (the accessor's count)", sparse.count, a.count));
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0)
    bad("a sparse byteOffset is negative");
  const int index_type = sparse.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    bad(fmt::format("sparse.indices.componentType {} is not 5121, 5123 or 5125", index_type));
  const size_t replaced = size_t(sparse.count);
  View indices;
  indices.component_type = index_type;
  indices.components = 1;
  indices.stride = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(index_type)));
  indices.base = checked_bytes(sparse.indices.bufferView, size_t(sparse.indices.byteOffset),
                               replaced, indices.stride, indices.stride, "sparse.indices: ", bad);
  View values = out;  // the same type, tightly packed
  values.stride = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType))) *
                  size_t(out.components);
  values.values.clear();
  values.base = checked_bytes(sparse.values.bufferView, size_t(sparse.values.byteOffset), replaced,
                              values.stride, values.stride, "sparse.values: ", bad);
  const size_t components = size_t(out.components);
  out.values.assign(out.count * components, 0.0);
  if (out.base)
    for (size_t i = 0; i < out.count; ++i)
      for (size_t c = 0; c < components; ++c) out.values[i * components + c] = out.raw(i, int(c));
  double previous = -1;
  for (size_t k = 0; k < replaced; ++k) {
    const double index = indices.raw(k, 0);
    if (index <= previous || index >= double(out.count))
      bad(fmt::format("sparse index {} is {}: sparse indices must increase strictly and stay "
                      "below the count {}",
                      k, index, out.count));
    previous = index;
    for (size_t c = 0; c < components; ++c)
      out.values[size_t(index) * components + c] = values.raw(k, int(c));
  }
  // An accessor of zero elements has nothing to read either way.
  if (out.values.empty()) out.base = nullptr;
}

glm::ivec2 GltfReader::texture_size(int material, int* texcoord_set) {
  *texcoord_set = 0;
  if (material < 0) return default_texture_;
  if (size_t(material) >= model_.materials.size())
    fail(fmt::format("material {} is outside the {} materials", material, model_.materials.size()));
  const tinygltf::TextureInfo& info =
      model_.materials[size_t(material)].pbrMetallicRoughness.baseColorTexture;
  if (info.index < 0) return default_texture_;
  if (size_t(info.index) >= model_.textures.size())
    fail(fmt::format("material {}: texture {} is outside the {} textures", material, info.index,
                     model_.textures.size()));
  if (info.texCoord < 0 || info.texCoord > 15)
    fail(fmt::format("material {}: texCoord {} is outside 0..15", material, info.texCoord));
  *texcoord_set = info.texCoord;
  const int image = model_.textures[size_t(info.index)].source;
  if (image < 0) return default_texture_;
  if (size_t(image) >= model_.images.size())
    fail(fmt::format("texture {}: image {} is outside the {} images", info.index, image,
                     model_.images.size()));
  if (size_t(image) < images_.size.size() && images_.size[size_t(image)]) {
    ++sized_primitives_;
    return *images_.size[size_t(image)];
  }
  return default_texture_;
}

void GltfReader::add_mesh(int mesh_index, const glm::dmat4& transform, int node) {
  if (mesh_index < 0 || size_t(mesh_index) >= model_.meshes.size())
    fail(fmt::format("mesh {} is outside the {} meshes", mesh_index, model_.meshes.size()));
  const tinygltf::Mesh& mesh = model_.meshes[size_t(mesh_index)];
  for (size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& primitive = mesh.primitives[p];
    ++primitives_;
    const std::string what = node >= 0 ? fmt::format("node {} mesh {} primitive {}", node, mesh_index, p)
                                       : fmt::format("mesh {} primitive {}", mesh_index, p);
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
      fail(fmt::format("{}: mode {} is not a glTF primitive mode (0 to 6: points, lines, line "
                       "loop, line strip, triangles, triangle strip, triangle fan)",
                       what, mode));
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      ++skipped_primitives_;  // points and lines draw no triangles
      continue;
    }
    const auto position_it = primitive.attributes.find("POSITION");
    if (position_it == primitive.attributes.end()) fail(what + ": no POSITION attribute");
    const View positions = accessor(position_it->second, what + " POSITION", {TINYGLTF_TYPE_VEC3},
                                    {TINYGLTF_COMPONENT_TYPE_FLOAT});
    int texcoord_set = 0;
    const glm::ivec2 texture = texture_size(primitive.material, &texcoord_set);
    View texcoords;
    const std::string texcoord_name = fmt::format("TEXCOORD_{}", texcoord_set);
    const auto texcoord_it = primitive.attributes.find(texcoord_name);
    if (texcoord_it == primitive.attributes.end()) {
      if (!missing_texcoord_)
        fail(fmt::format("{}: no {} attribute, which {}; cdsim needs a texture coordinate at every "
                         "vertex, or a scene file's \"missing_texcoord\": [s, t] to stand for "
                         "the missing ones",
                         what, texcoord_name,
                         primitive.material >= 0 &&
                                 model_.materials[size_t(primitive.material)]
                                         .pbrMetallicRoughness.baseColorTexture.index >= 0
                             ? fmt::format("material {}'s base colour texture reads (texCoord {})",
                                           primitive.material, texcoord_set)
                             : std::string("cdsim reads when the primitive has no texture")));
      ++defaulted_primitives_;
    } else {
      texcoords = accessor(texcoord_it->second, what + " TEXCOORD", {TINYGLTF_TYPE_VEC2},
                           {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
      if (texcoords.count != positions.count)
        fail(fmt::format("{}: {} texture coordinates for {} positions", what, texcoords.count,
                         positions.count));
    }
    std::vector<size_t> order;
    if (primitive.indices >= 0) {
      const View indices = accessor(primitive.indices, what + " indices", {TINYGLTF_TYPE_SCALAR},
                                    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
      order.reserve(indices.count);
      for (size_t i = 0; i < indices.count; ++i) {
        const double index = indices.get(i, 0);
        if (index >= double(positions.count))
          fail(fmt::format("{}: index {} is {}, outside the {} vertices", what, i, index,
                           positions.count));
        order.push_back(size_t(index));
      }
    } else {
      order.resize(positions.count);
      for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    }
    const auto vertex = [&](size_t i) {
      MeshVertex v;
      const glm::dvec4 world =
          transform * glm::dvec4(positions.get(i, 0), positions.get(i, 1), positions.get(i, 2), 1);
      v.position = glm::dvec3(world);
      v.texcoord = texcoords.present() ? glm::dvec2(texcoords.get(i, 0), texcoords.get(i, 1))
                                       : *missing_texcoord_;
      return v;
    };
    const auto add = [&](size_t t, size_t a, size_t b, size_t c) {
      builder_.add(vertex(a), vertex(b), vertex(c), texture,
                   [&] { return fmt::format("{} triangle {}", what, t); });
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (size_t t = 0; t + 2 < order.size(); t += 3) add(t / 3, order[t], order[t + 1], order[t + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t t = 0; t + 2 < order.size(); ++t)
        if (t % 2 == 0)
          add(t, order[t], order[t + 1], order[t + 2]);
        else
          add(t, order[t + 1], order[t], order[t + 2]);
    } else {
      for (size_t t = 0; t + 2 < order.size(); ++t) add(t, order[0], order[t + 1], order[t + 2]);
    }
  }
}

glm::dmat4 node_transform(const tinygltf::Node& node, const std::string& fail_prefix) {
  const auto finite = [&](const std::vector<double>& values, size_t count, const char* field) {
    if (values.empty()) return false;
    if (values.size() != count)
      throw InputError(fmt::format("{}: {} has {} numbers, expected {}", fail_prefix, field,
                                   values.size(), count));
    for (size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i]) || std::fabs(values[i]) > limits::kMaxMeshCoordinate)
        throw InputError(fmt::format("{}: {}[{}] is {}, not a finite number within +-{:g}",
                                     fail_prefix, field, i, values[i], limits::kMaxMeshCoordinate));
    return true;
  };
  if (finite(node.matrix, 16, "matrix")) {
    // glTF 2.0 §5.25: a node matrix is a TRS transform, so its last row (the
    // elements 3, 7, 11, 15 in column-major order) is 0, 0, 0, 1. Any other
    // row would make it projective, which a mesh position (w = 1) cannot take
    // without a divide that glTF does not define.
    const std::vector<double>& m = node.matrix;
    if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1)
      throw InputError(fmt::format("{}: matrix's last row is ({}, {}, {}, {}) (elements 3, 7, 11 "
                                   "and 15); a node matrix must be affine, with last row (0, 0, "
                                   "0, 1)",
                                   fail_prefix, m[3], m[7], m[11], m[15]));
    return glm::make_mat4(m.data());
  }
  glm::dmat4 m(1.0);
  if (finite(node.translation, 3, "translation"))
    m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  if (finite(node.rotation, 4, "rotation")) {
    // glTF stores (x, y, z, w); glm's constructor takes (w, x, y, z).
    glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    // A unit quaternion is required (glTF 2.0 §5.25). One written with a few
    // digits is off by far less than the tolerance and is normalised, so
    // that the matrix is a rotation; a zero one is no rotation at all, and
    // one further off is a mistake that mat4_cast would turn into a shear.
    const double length = glm::length(q);
    if (!(std::fabs(length - 1) <= kQuaternionTolerance))
      throw InputError(fmt::format("{}: rotation ({}, {}, {}, {}) has length {}; glTF requires a "
                                   "unit quaternion (length 1 within {})",
                                   fail_prefix, node.rotation[0], node.rotation[1],
                                   node.rotation[2], node.rotation[3], length,
                                   kQuaternionTolerance));
    m = m * glm::mat4_cast(q / length);
  }
  if (finite(node.scale, 3, "scale"))
    m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  return m;
}

void GltfReader::visit(int node_index, const glm::dmat4& parent, int depth) {
  if (node_index < 0 || size_t(node_index) >= model_.nodes.size())
    fail(fmt::format("node {} is outside the {} nodes", node_index, model_.nodes.size()));
  if (depth > limits::kMaxNodeDepth)
    fail(fmt::format("node hierarchy deeper than {} at node {}", limits::kMaxNodeDepth, node_index));
  if (on_path_[size_t(node_index)])
    fail(fmt::format("node {} is its own ancestor: the node hierarchy has a cycle", node_index));
  if (++node_visits_ > (size_t{1} << 20))
    fail("more than 1048576 node instances: the node hierarchy multiplies out too far");
  const tinygltf::Node& node = model_.nodes[size_t(node_index)];
  const std::string where = fmt::format("{}: node {}{}", name_, node_index,
                                        node.name.empty() ? "" : " " + quote_bytes(node.name));
  const glm::dmat4 transform = parent * node_transform(node, where);
  // Each value may be finite and the product of the hierarchy still overflow.
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(transform[column][row]) ||
          std::fabs(transform[column][row]) > limits::kMaxMeshCoordinate)
        throw InputError(fmt::format(
            "{}: its transform, with its ancestors', overflows: element [{}][{}] is {} (node "
            "transforms must keep every value within +-{:g})",
            where, row, column, transform[column][row], limits::kMaxMeshCoordinate));
  on_path_[size_t(node_index)] = true;
  if (node.mesh >= 0) add_mesh(node.mesh, transform, node_index);
  for (int child : node.children) visit(child, transform, depth + 1);
  on_path_[size_t(node_index)] = false;
}

LoadedGltf GltfReader::read() {
  on_path_.assign(model_.nodes.size(), false);
  std::string how;
  if (!model_.scenes.empty()) {
    int scene = model_.defaultScene < 0 ? 0 : model_.defaultScene;
    if (size_t(scene) >= model_.scenes.size())
      fail(fmt::format("default scene {} is outside the {} scenes", scene, model_.scenes.size()));
    for (int node : model_.scenes[size_t(scene)].nodes) visit(node, glm::dmat4(1.0), 0);
    how = fmt::format("scene {}", scene);
  } else {
    // No scene: every mesh once, untransformed (glTF 2.0 §3.5 leaves this to the reader).
    for (size_t m = 0; m < model_.meshes.size(); ++m) add_mesh(int(m), glm::dmat4(1.0), -1);
    how = "no scene, every mesh once";
  }
  if (builder_.triangle_count() == 0) {
    if (model_.meshes.empty()) fail("no triangle to draw: the file has no meshes");
    if (primitives_ == 0)
      fail(fmt::format("no triangle to draw: {} instances no mesh primitive", how));
    if (skipped_primitives_ == primitives_)
      fail(fmt::format("no usable primitive: every primitive of {} ({} in all) is points or "
                       "lines; cdsim draws triangles, triangle strips and triangle fans",
                       how, primitives_));
    fail(fmt::format("no triangle to draw: the {} triangle primitives of {} have fewer than 3 "
                     "vertices each",
                     primitives_ - skipped_primitives_, how));
  }
  LoadedGltf out;
  out.summary = fmt::format("{}: {} primitives ({} with a known texture size, {} points/lines "
                            "skipped), {} triangles",
                            how, primitives_, sized_primitives_, skipped_primitives_,
                            builder_.triangle_count());
  if (defaulted_primitives_)
    out.summary += fmt::format(", {} primitives without texture coordinates given ({}, {})",
                               defaulted_primitives_, missing_texcoord_->x, missing_texcoord_->y);
  out.mesh = builder_.take();
  return out;
}

uint32_t little_endian_u32(const uint8_t* bytes) {
  return uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 |
         uint32_t(bytes[3]) << 24;
}

// A chunk type as text for a message: 'JSON', 'BIN\x00'.
std::string chunk_type(const uint8_t* bytes) {
  return quote_bytes(std::string_view(reinterpret_cast<const char*>(bytes), 4));
}

// The JSON chunk of a .glb, after its header and chunk layout are checked
// field by field (tinygltf says only "Invalid glTF binary." for most faults).
std::string_view glb_json_chunk(const uint8_t* data, size_t size, const std::string& name) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}: binary glTF (.glb): {}", name, what));
  };
  if (size < 12)
    fail(fmt::format("{} bytes, shorter than the 12-byte header (magic, version, length)", size));
  const uint32_t version = little_endian_u32(data + 4);
  if (version != 2) fail(fmt::format("version {} at byte 4; only version 2 is read", version));
  const uint32_t length = little_endian_u32(data + 8);
  if (length > size)
    fail(fmt::format("the header's length at byte 8 is {} bytes, but the file has {}", length, size));
  if (length < 20)
    fail(fmt::format("the header's length at byte 8 is {} bytes, too short for the JSON chunk's "
                     "8-byte header at byte 12",
                     length));
  const uint32_t json_length = little_endian_u32(data + 12);
  if (std::memcmp(data + 16, "JSON", 4) != 0)
    fail(fmt::format("the first chunk (byte 12) has type {}; it must be 'JSON'", chunk_type(data + 16)));
  if (json_length == 0) fail("the JSON chunk (byte 12) is empty");
  if (uint64_t(json_length) > uint64_t(length) - 20)
    fail(fmt::format("the JSON chunk's length at byte 12 is {} bytes, but only {} follow its header "
                     "within the {} bytes the header gives",
                     json_length, length - 20, length));
  const uint64_t bin_at = 20 + uint64_t(json_length);
  if (bin_at < length) {
    if (uint64_t(length) - bin_at < 8)
      fail(fmt::format("{} bytes after the JSON chunk (byte {}) are too few for a chunk header",
                       uint64_t(length) - bin_at, bin_at));
    const uint32_t bin_length = little_endian_u32(data + bin_at);
    if (std::memcmp(data + bin_at + 4, "BIN\0", 4) != 0)
      fail(fmt::format("the chunk at byte {} has type {}; after the JSON chunk cdsim reads only a "
                       "'BIN\\x00' chunk",
                       bin_at, chunk_type(data + bin_at + 4)));
    if (uint64_t(bin_length) > uint64_t(length) - bin_at - 8)
      fail(fmt::format("the BIN chunk's length at byte {} is {} bytes, but only {} follow its "
                       "header within the {} bytes the header gives",
                       bin_at, bin_length, uint64_t(length) - bin_at - 8, length));
  }
  return {reinterpret_cast<const char*>(data + 20), json_length};
}

// Checks made on the JSON text before tinygltf parses it: the nesting depth
// (tinygltf converts `extras` and `extensions` recursively), the extensions
// the file requires (a file that requires Draco would otherwise fail first on
// the accessors Draco leaves without data), and keys repeated in one object
// (glTF 2.0 §3.2: the names within a JSON object must be unique).
void check_gltf_json(std::string_view json_text, const std::string& name) {
  check_json_depth(json_text, name);
  using nlohmann::json;
  // Only the top level's extensionsRequired is kept; the rest is dropped as it is read.
  const json::parser_callback_t required_only = [](int depth, json::parse_event_t event,
                                                    json& parsed) {
    return !(depth == 1 && event == json::parse_event_t::key && parsed != "extensionsRequired");
  };
  json root;
  try {
    root = json::parse(json_text.begin(), json_text.end(), required_only);
  } catch (const json::parse_error& e) {
    throw InputError(fmt::format("{}: not valid JSON at byte {}: {}", name, e.byte, e.what()));
  } catch (const json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", name, e.what()));
  }
  if (!root.is_object())
    throw InputError(fmt::format("{}: expected a JSON object, found {}", name, root.type_name()));
  if (root.contains("extensionsRequired")) {
    const json& required = root["extensionsRequired"];
    if (!required.is_array())
      throw InputError(fmt::format("{}: extensionsRequired is {}, not an array of names", name,
                                   required.type_name()));
    for (const json& extension : required) {
      if (!extension.is_string())
        throw InputError(fmt::format("{}: extensionsRequired holds {}, not an extension name", name,
                                     extension.type_name()));
      const std::string& text = extension.get_ref<const std::string&>();
      if (!supported_required_extension(text))
        throw InputError(fmt::format("{}: requires the extension {}, which cdsim does not support "
                                     "(of required extensions it accepts only KHR_materials_* and "
                                     "KHR_lights_punctual, which change nothing it reads)",
                                     name, quote_bytes(text, 80)));
    }
  }
  check_json_unique_keys(json_text, name);
}

LoadedGltf load(const uint8_t* data, size_t size, const std::string& name,
                const std::string& base_dir, bool memory_only, glm::ivec2 default_texture,
                const std::optional<glm::dvec2>& missing_texcoord) {
  if (size > UINT_MAX)
    throw InputError(fmt::format("{}: {} bytes is too large for tinygltf", name, size));
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  // A byte-order mark before the JSON of a .gltf is ignored.
  const std::string_view json =
      binary ? glb_json_chunk(data, size, name)
             : without_utf8_bom(std::string_view(reinterpret_cast<const char*>(data), size));
  check_gltf_json(json, binary ? name + " (JSON chunk)" : name);
  tinygltf::TinyGLTF loader;
  ImageSizes images;
  images.name = name;
  loader.SetImageLoader(&record_image_size, &images);
  if (memory_only)
    loader.SetFsCallbacks({&no_file_exists, &no_expand, &no_read, &no_write, nullptr});
  else
    loader.SetFsCallbacks({&file_exists, &no_expand, &read_capped, &no_write, nullptr});
  tinygltf::Model model;
  std::string err, warn;
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, unsigned(size), base_dir)
             : loader.LoadASCIIFromString(&model, &err, &warn, json.data(), unsigned(json.size()),
                                          base_dir);
  while (!err.empty() && err.back() == '\n') err.pop_back();
  for (char& c : err)
    if (c == '\n') c = ';';
  if (!ok)
    throw InputError(fmt::format("{}: not a readable glTF 2.0 {} file: {}", name,
                                 binary ? "binary (.glb)" : "JSON (.gltf)", err));
  if (!images.error.empty()) throw InputError(images.error);
  // Images stored in buffer views: bounds checked here, then only the header read.
  images.size.resize(model.images.size());
  for (size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& image = model.images[i];
    if (image.bufferView < 0) continue;
    if (size_t(image.bufferView) >= model.bufferViews.size()) continue;
    const tinygltf::BufferView& view = model.bufferViews[size_t(image.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) continue;
    const auto& bytes = model.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > bytes.size() || view.byteLength > bytes.size() - view.byteOffset)
      throw InputError(fmt::format("{}: image {}: buffer view {} lies outside its buffer", name, i,
                                   image.bufferView));
    images.size[i] = image_size_from_memory(bytes.data() + view.byteOffset, view.byteLength,
                                            fmt::format("{}: image {}", name, i));
  }
  return GltfReader(model, images, name, default_texture, missing_texcoord).read();
}

}  // namespace

LoadedGltf load_gltf(const std::string& path, glm::ivec2 default_texture_size,
                     const std::optional<glm::dvec2>& missing_texcoord) {
  const std::vector<uint8_t> bytes = read_file_bytes(path);
  return load(bytes.data(), bytes.size(), path, directory_of(path), false, default_texture_size,
              missing_texcoord);
}

LoadedGltf load_gltf_from_memory(const uint8_t* data, size_t size, const std::string& name,
                                 glm::ivec2 default_texture_size,
                                 const std::optional<glm::dvec2>& missing_texcoord) {
  return load(data, size, name, "", true, default_texture_size, missing_texcoord);
}

}  // namespace cdsim
