#include "bsp.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>

#include "file_io.hpp"
#include "image_size.hpp"
#include "limits.hpp"
#include "mesh_builder.hpp"
#include "pk3.hpp"
#include "strict_text.hpp"

namespace cdsim {

namespace {

constexpr const char* kLumpNames[17] = {
    "entities", "shaders", "planes",  "nodes",     "leafs",     "leaffaces",
    "leafbrushes", "models", "brushes", "brushsides", "vertexes", "meshverts",
    "effects",  "faces",   "lightmaps", "lightvols", "visdata"};
enum Lump { kEntities = 0, kShaders = 1, kVertexes = 10, kMeshverts = 11, kFaces = 13 };
constexpr size_t kHeaderBytes = 8 + 17 * 8;
constexpr size_t kShaderBytes = 72, kVertexBytes = 44, kMeshvertBytes = 4, kFaceBytes = 104;
constexpr int32_t kSurfNodraw = 0x80;

// Little-endian fields at checked offsets.
class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  size_t size() const { return size_; }
  const uint8_t* at(size_t offset) const { return data_ + offset; }
  int32_t i32(size_t offset) const {
    uint32_t value = 0;
    for (size_t i = 0; i < 4; ++i) value |= uint32_t{data_[offset + i]} << (8 * i);
    int32_t out;
    std::memcpy(&out, &value, 4);
    return out;
  }
  float f32(size_t offset) const {
    const int32_t bits = i32(offset);
    float out;
    std::memcpy(&out, &bits, 4);
    return out;
  }

 private:
  const uint8_t* data_;
  size_t size_;
};

struct LumpRange {
  size_t offset = 0, length = 0, count = 0;
};

class BspReader {
 public:
  BspReader(const uint8_t* data, size_t size, std::string name, glm::ivec2 default_texture,
            const TextureSizeLookup& lookup)
      : bytes_(data, size), name_(std::move(name)), default_texture_(default_texture),
        lookup_(lookup), builder_(name_) {}

  BspMap read();

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: {}", name_, what));
  }
  LumpRange lump(int index, size_t record_bytes) const;
  void read_shaders();
  void read_vertices();
  void read_meshverts();
  void read_faces();
  void read_spawns();
  glm::ivec2 texture_of(size_t shader);
  void add_patch(size_t face, size_t face_offset, int first, int width, int height,
                 glm::ivec2 texture);

  Bytes bytes_;
  std::string name_;
  glm::ivec2 default_texture_;
  const TextureSizeLookup& lookup_;
  MeshBuilder builder_;
  struct Shader {
    std::string name;
    int32_t flags = 0;
    bool looked_up = false;
    std::optional<glm::ivec2> size;
  };
  std::vector<Shader> shaders_;
  std::vector<MeshVertex> vertices_;
  std::vector<int32_t> meshverts_;
  BspMap map_;
};

LumpRange BspReader::lump(int index, size_t record_bytes) const {
  const size_t entry = 8 + 8 * static_cast<size_t>(index);
  const int32_t offset = bytes_.i32(entry), length = bytes_.i32(entry + 4);
  const auto where = [&] {
    return fmt::format("lump {} ({}), directory entry at byte {}", index, kLumpNames[index], entry);
  };
  if (offset < 0 || length < 0)
    fail(fmt::format("{}: negative offset {} or length {}", where(), offset, length));
  if (uint64_t(offset) + uint64_t(length) > bytes_.size())
    fail(fmt::format("{}: bytes {}..{} lie past the end of the {}-byte file", where(), offset,
                     uint64_t(offset) + uint64_t(length), bytes_.size()));
  if (length % record_bytes != 0)
    fail(fmt::format("{}: length {} is not a multiple of the {}-byte record", where(), length,
                     record_bytes));
  return {size_t(offset), size_t(length), size_t(length) / record_bytes};
}

void BspReader::read_shaders() {
  const LumpRange range = lump(kShaders, kShaderBytes);
  for (size_t i = 0; i < range.count; ++i) {
    const size_t at = range.offset + i * kShaderBytes;
    const char* text = reinterpret_cast<const char*>(bytes_.at(at));
    Shader shader;
    shader.name.assign(text, strnlen(text, 64));
    shader.flags = bytes_.i32(at + 64);
    shaders_.push_back(std::move(shader));
  }
}

void BspReader::read_vertices() {
  const LumpRange range = lump(kVertexes, kVertexBytes);
  vertices_.reserve(range.count);
  for (size_t i = 0; i < range.count; ++i) {
    const size_t at = range.offset + i * kVertexBytes;
    MeshVertex v;
    v.position = {bytes_.f32(at), bytes_.f32(at + 4), bytes_.f32(at + 8)};
    v.texcoord = {bytes_.f32(at + 12), bytes_.f32(at + 16)};
    if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) ||
        !std::isfinite(v.position.z) || !std::isfinite(v.texcoord.x) ||
        !std::isfinite(v.texcoord.y))
      fail(fmt::format("lump 10 (vertexes): vertex {} at byte {} is not finite: position ({}, {}, "
                       "{}), texcoord ({}, {})",
                       i, at, v.position.x, v.position.y, v.position.z, v.texcoord.x,
                       v.texcoord.y));
    vertices_.push_back(v);
  }
}

void BspReader::read_meshverts() {
  const LumpRange range = lump(kMeshverts, kMeshvertBytes);
  meshverts_.reserve(range.count);
  for (size_t i = 0; i < range.count; ++i) meshverts_.push_back(bytes_.i32(range.offset + 4 * i));
}

glm::ivec2 BspReader::texture_of(size_t shader) {
  Shader& s = shaders_[shader];
  if (!s.looked_up) {
    s.looked_up = true;
    if (lookup_) s.size = lookup_(s.name);
    ++map_.stats.shaders;
    if (s.size) ++map_.stats.shaders_sized;
  }
  return s.size.value_or(default_texture_);
}

// A 3x3 biquadratic Bézier patch evaluated on a (level+1)^2 grid.
void BspReader::add_patch(size_t face, size_t face_offset, int first, int width, int height,
                          glm::ivec2 texture) {
  const int level = kPatchTessellationLevel;
  const auto bernstein = [](double t) {
    return std::array<double, 3>{(1 - t) * (1 - t), 2 * t * (1 - t), t * t};
  };
  std::vector<MeshVertex> grid(size_t((level + 1) * (level + 1)));
  for (int py = 0; py < (height - 1) / 2; ++py) {
    for (int px = 0; px < (width - 1) / 2; ++px) {
      for (int a = 0; a <= level; ++a) {
        const auto bt = bernstein(double(a) / level);
        for (int b = 0; b <= level; ++b) {
          const auto bs = bernstein(double(b) / level);
          MeshVertex out;
          for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i) {
              const MeshVertex& c =
                  vertices_[size_t(first + (2 * py + j) * width + (2 * px + i))];
              out.position += bt[size_t(j)] * bs[size_t(i)] * c.position;
              out.texcoord += bt[size_t(j)] * bs[size_t(i)] * c.texcoord;
            }
          grid[size_t(a * (level + 1) + b)] = out;
        }
      }
      for (int a = 0; a < level; ++a)
        for (int b = 0; b < level; ++b) {
          const auto at = [&](int row, int column) { return grid[size_t(row * (level + 1) + column)]; };
          const auto where = [&] {
            return fmt::format("face {} at byte {} (patch {},{})", face, face_offset, px, py);
          };
          builder_.add(at(a, b), at(a + 1, b), at(a, b + 1), texture, where);
          builder_.add(at(a, b + 1), at(a + 1, b), at(a + 1, b + 1), texture, where);
        }
    }
  }
}

void BspReader::read_faces() {
  const LumpRange range = lump(kFaces, kFaceBytes);
  map_.stats.faces = range.count;
  for (size_t f = 0; f < range.count; ++f) {
    const size_t at = range.offset + f * kFaceBytes;
    const int32_t shader = bytes_.i32(at), type = bytes_.i32(at + 8);
    const int32_t first_vertex = bytes_.i32(at + 12), vertex_count = bytes_.i32(at + 16);
    const int32_t first_meshvert = bytes_.i32(at + 20), meshvert_count = bytes_.i32(at + 24);
    const int32_t patch_width = bytes_.i32(at + 96), patch_height = bytes_.i32(at + 100);
    const auto bad = [&](const std::string& what) {
      fail(fmt::format("lump 13 (faces): face {} at byte {}: {}", f, at, what));
    };
    if (type < 1 || type > 4)
      bad(fmt::format("type {} is not 1 (polygon), 2 (patch), 3 (mesh) or 4 (billboard)", type));
    if (type == 4) {
      ++map_.stats.billboards;
      continue;
    }
    if (shader < 0 || size_t(shader) >= shaders_.size())
      bad(fmt::format("shader index {} is outside the {} shaders", shader, shaders_.size()));
    if (shaders_[size_t(shader)].flags & kSurfNodraw) {
      ++map_.stats.nodraw;
      continue;
    }
    if (first_vertex < 0 || vertex_count < 0 ||
        int64_t(first_vertex) + vertex_count > int64_t(vertices_.size()))
      bad(fmt::format("vertices {}..{} are outside the {} vertices", first_vertex,
                      int64_t(first_vertex) + vertex_count, vertices_.size()));
    const glm::ivec2 texture = texture_of(size_t(shader));
    if (type == 2) {
      ++map_.stats.patches;
      if (patch_width < 3 || patch_height < 3 || patch_width % 2 == 0 || patch_height % 2 == 0)
        bad(fmt::format("patch of {}x{} control points; both must be odd and at least 3",
                        patch_width, patch_height));
      if (int64_t(patch_width) * patch_height != vertex_count)
        bad(fmt::format("patch of {}x{} control points, but the face has {} vertices",
                        patch_width, patch_height, vertex_count));
      add_patch(f, at, first_vertex, patch_width, patch_height, texture);
      continue;
    }
    ++(type == 1 ? map_.stats.polygons : map_.stats.meshes);
    if (first_meshvert < 0 || meshvert_count < 0 ||
        int64_t(first_meshvert) + meshvert_count > int64_t(meshverts_.size()))
      bad(fmt::format("mesh vertices {}..{} are outside the {} mesh vertices", first_meshvert,
                      int64_t(first_meshvert) + meshvert_count, meshverts_.size()));
    if (meshvert_count % 3 != 0)
      bad(fmt::format("{} mesh vertices do not make whole triangles", meshvert_count));
    for (int32_t k = 0; k < meshvert_count; k += 3) {
      std::array<MeshVertex, 3> corner;
      for (int32_t i = 0; i < 3; ++i) {
        const int32_t offset = meshverts_[size_t(first_meshvert + k + i)];
        if (offset < 0 || offset >= vertex_count)
          bad(fmt::format("mesh vertex {} (index {} in lump 11) is {}, outside the face's {} "
                          "vertices",
                          k + i, first_meshvert + k + i, offset, vertex_count));
        corner[size_t(i)] = vertices_[size_t(first_vertex + offset)];
      }
      builder_.add(corner[0], corner[1], corner[2], texture,
                   [&] { return fmt::format("face {} at byte {}", f, at); });
    }
  }
}

// The numbers of an entity value ("0 -200 16"), each strict (strict_text.hpp)
// and within the camera's range, since a spawn point becomes a camera; empty
// when any is not.
std::vector<double> parse_numbers(const std::string& text) {
  std::vector<double> numbers;
  bool ok = true;
  for_each_word(text, [&](std::string_view word) {
    const ParsedNumber parsed = parse_number(word, limits::kMaxCameraCoordinate);
    ok = ok && parsed.ok();
    numbers.push_back(parsed.value);
  });
  if (!ok) numbers.clear();
  return numbers;
}

void BspReader::read_spawns() {
  const LumpRange range = lump(kEntities, 1);
  const char* text = reinterpret_cast<const char*>(bytes_.at(range.offset));
  const std::string entities(text, strnlen(text, range.length));
  const auto blocks = parse_entities(entities, name_ + ": lump 0 (entities)");
  for (size_t e = 0; e < blocks.size(); ++e) {
    std::map<std::string, std::string> keys(blocks[e].begin(), blocks[e].end());
    const std::string classname = keys["classname"];
    if (classname != "info_player_deathmatch" && classname != "info_player_start") continue;
    BspSpawnPoint spawn;
    spawn.classname = classname;
    spawn.entity = static_cast<int>(e);
    const auto bad = [&](const std::string& key, size_t count) {
      fail(fmt::format("lump 0 (entities): entity {} ({}): \"{}\" {} is not {} finite numbers "
                       "(of magnitude at most {:g})",
                       e, classname, key, quote_bytes(keys[key], 40, '"'), count,
                       limits::kMaxCameraCoordinate));
    };
    const std::vector<double> origin = parse_numbers(keys["origin"]);
    if (origin.size() != 3) bad("origin", 3);
    spawn.origin = {origin[0], origin[1], origin[2]};
    if (keys.count("angles")) {
      const std::vector<double> angles = parse_numbers(keys["angles"]);
      if (angles.size() != 3) bad("angles", 3);
      spawn.pitch_degrees = angles[0];
      spawn.yaw_degrees = angles[1];
    } else if (keys.count("angle")) {
      const std::vector<double> angle = parse_numbers(keys["angle"]);
      if (angle.size() != 1) bad("angle", 1);
      spawn.yaw_degrees = angle[0];
    }
    map_.spawns.push_back(spawn);
  }
}

BspMap BspReader::read() {
  const auto truncated = [&] {
    fail(fmt::format("truncated: {} bytes, but a Quake 3 BSP header needs {}", bytes_.size(),
                     kHeaderBytes));
  };
  if (bytes_.size() < 4) truncated();
  if (std::memcmp(bytes_.at(0), "IBSP", 4) != 0) {
    std::string magic;
    for (size_t i = 0; i < 4; ++i) {
      const uint8_t c = *bytes_.at(i);
      magic += (c >= 32 && c < 127) ? std::string(1, char(c)) : fmt::format("\\x{:02x}", c);
    }
    fail(fmt::format("magic '{}' at byte 0 is not 'IBSP': not a Quake 3 BSP", magic));
  }
  if (bytes_.size() < 8) truncated();
  const int32_t version = bytes_.i32(4);
  if (version != 46)
    fail(fmt::format("version {} at byte 4; only Quake 3 / OpenArena version 46 is read", version));
  if (bytes_.size() < kHeaderBytes) truncated();
  read_shaders();
  read_vertices();
  read_meshverts();
  read_spawns();
  read_faces();
  map_.mesh = builder_.take();
  return std::move(map_);
}

}  // namespace

std::vector<std::vector<std::pair<std::string, std::string>>> parse_entities(
    const std::string& text, const std::string& name) {
  std::vector<std::vector<std::pair<std::string, std::string>>> blocks;
  size_t pos = 0;
  const auto fail = [&](size_t at, const std::string& what) {
    throw InputError(fmt::format("{}: byte {}: {}", name, at, what));
  };
  const auto skip_space = [&] {
    for (;;) {
      while (pos < text.size() && static_cast<unsigned char>(text[pos]) <= ' ') ++pos;
      if (pos + 1 < text.size() && text[pos] == '/' && text[pos + 1] == '/') {
        while (pos < text.size() && text[pos] != '\n') ++pos;
        continue;
      }
      return;
    }
  };
  const auto quoted = [&](const char* what) {
    skip_space();
    if (pos >= text.size()) fail(pos, fmt::format("text ends where a {} was expected", what));
    if (text[pos] != '"')
      fail(pos, fmt::format("expected a quoted {}, found {}", what, quote_bytes(text.substr(pos, 1))));
    const size_t start = ++pos;
    const size_t end = text.find('"', start);
    if (end == std::string::npos) fail(start - 1, fmt::format("unterminated quoted {}", what));
    pos = end + 1;
    return text.substr(start, end - start);
  };
  for (;;) {
    skip_space();
    if (pos >= text.size()) break;
    if (text[pos] != '{')
      fail(pos, fmt::format("expected '{{' to open an entity, found {}", quote_bytes(text.substr(pos, 1))));
    ++pos;
    std::vector<std::pair<std::string, std::string>> block;
    for (;;) {
      skip_space();
      if (pos >= text.size()) fail(pos, fmt::format("entity {} is not closed by '}}'", blocks.size()));
      if (text[pos] == '}') {
        ++pos;
        break;
      }
      std::string key = quoted("key");
      std::string value = quoted("value");
      block.emplace_back(std::move(key), std::move(value));
    }
    blocks.push_back(std::move(block));
  }
  return blocks;
}

BspMap load_bsp_from_memory(const uint8_t* data, size_t size, const std::string& name,
                            glm::ivec2 default_texture_size, const TextureSizeLookup& lookup) {
  return BspReader(data, size, name, default_texture_size, lookup).read();
}

namespace {

// Quake 3 looks for a shader's image as .tga, then .jpg; OpenArena adds .png.
std::vector<std::string> image_candidates(const std::string& shader) {
  std::string stem = shader;
  for (const char* ext : {".tga", ".jpg", ".png"})
    if (ends_with_ignoring_case(stem, ext)) stem.resize(stem.size() - 4);
  return {stem + ".tga", stem + ".jpg", stem + ".png"};
}

}  // namespace

namespace {

// Quake 3's search path for a map's images: the map's own archive, then the
// other .pk3 files of its directory, later names first (a later pk3 overrides
// an earlier one in Quake), then loose files under `loose_root`. Archives are
// opened only when a lookup needs them; one that cannot be opened is skipped.
class TextureSearch {
 public:
  // `directory`: where sibling archives are looked for; nothing when empty.
  TextureSearch(const Pk3Archive* own, std::optional<std::string> directory, std::string skip,
                std::string loose_root)
      : own_(own), directory_(std::move(directory)), skip_(std::move(skip)),
        loose_root_(std::move(loose_root)) {}

  std::optional<glm::ivec2> operator()(const std::string& shader) {
    const std::vector<std::string> candidates = image_candidates(shader);
    if (own_)
      if (auto size = find(*own_, candidates)) return size;
    open_siblings();
    for (const Pk3Archive& archive : siblings_)
      if (auto size = find(archive, candidates)) return size;
    if (!loose_root_.empty())
      for (const std::string& candidate : candidates)
        if (auto size = image_size_from_file(loose_root_ + candidate)) return size;
    return std::nullopt;
  }

 private:
  static std::optional<glm::ivec2> find(const Pk3Archive& archive,
                                        const std::vector<std::string>& candidates) {
    for (const std::string& candidate : candidates)
      if (archive.contains(candidate))
        if (const auto image = archive.read(candidate))
          return image_size_from_memory(image->data(), image->size(), archive.name() + ":" + candidate);
    return std::nullopt;
  }

  void open_siblings() {
    if (siblings_opened_ || !directory_) return;
    siblings_opened_ = true;
    const std::string& directory = *directory_;
    std::vector<std::string> names;
    std::error_code error;
    for (const auto& entry : std::filesystem::directory_iterator(
             directory.empty() ? std::string(".") : directory, error)) {
      const std::string name = entry.path().filename().string();
      if (ends_with_ignoring_case(name, ".pk3") && name != skip_) names.push_back(name);
    }
    std::sort(names.begin(), names.end(), std::greater<>());
    for (const std::string& name : names) {
      try {
        siblings_.push_back(Pk3Archive::open_file(directory + name));
      } catch (const InputError&) {
      }
    }
  }

  const Pk3Archive* own_;
  std::optional<std::string> directory_;
  std::string skip_, loose_root_;
  bool siblings_opened_ = false;
  std::vector<Pk3Archive> siblings_;
};

}  // namespace

BspMap load_bsp_from_archive(const Pk3Archive& archive, const std::string& entry,
                             glm::ivec2 default_texture_size) {
  const auto bytes = archive.read(entry);
  if (!bytes) throw InputError(fmt::format("{}: the archive has no entry '{}'", archive.name(), entry));
  const TextureSizeLookup lookup = [&](const std::string& shader) {
    return TextureSearch(&archive, std::nullopt, "", "")(shader);
  };
  return load_bsp_from_memory(bytes->data(), bytes->size(), archive.name() + ":" + entry,
                              default_texture_size, lookup);
}

BspMap load_bsp(const std::string& spec, glm::ivec2 default_texture_size) {
  if (const auto member = split_pk3_spec(spec)) {
    const Pk3Archive archive = Pk3Archive::open_file(member->first);
    if (!archive.contains(member->second)) {
      std::vector<std::string> maps;
      for (const std::string& entry : archive.entries())
        if (ends_with_ignoring_case(entry, ".bsp")) maps.push_back(entry);
      const size_t shown = std::min<size_t>(maps.size(), 8);
      throw InputError(fmt::format(
          "{}: the archive has no entry '{}'; it holds {} maps{}{}{}", member->first,
          member->second, maps.size(), shown ? ": " : "",
          fmt::join(maps.begin(), maps.begin() + static_cast<std::ptrdiff_t>(shown), ", "),
          maps.size() > shown ? ", ..." : ""));
    }
    const auto bytes = archive.read(member->second);
    const std::string directory = directory_of(member->first);
    TextureSearch search(&archive, directory, member->first.substr(directory.size()), "");
    const TextureSizeLookup lookup = [&](const std::string& shader) { return search(shader); };
    return load_bsp_from_memory(bytes->data(), bytes->size(), spec, default_texture_size, lookup);
  }
  const std::vector<uint8_t> bytes = read_file_bytes(spec);
  std::string root = directory_of(spec);
  if (ends_with_ignoring_case(root, "maps/")) root.resize(root.size() - 5);
  TextureSearch search(nullptr, root, "", root.empty() ? std::string("./") : root);
  const TextureSizeLookup lookup = [&](const std::string& shader) { return search(shader); };
  return load_bsp_from_memory(bytes.data(), bytes.size(), spec, default_texture_size, lookup);
}

Camera spawn_camera(const BspSpawnPoint& spawn, int width, int height) {
  Camera camera;
  camera.eye = spawn.origin + glm::dvec3(0, 0, kSpawnLift + kViewHeight);
  const double yaw = glm::radians(spawn.yaw_degrees), pitch = glm::radians(spawn.pitch_degrees);
  const glm::dvec3 forward{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                           -std::sin(pitch)};
  camera.target = camera.eye + 64.0 * forward;
  camera.up = {0, 0, 1};
  const double half_x = glm::radians(kSpawnHorizontalFov / 2);
  camera.fov_y_degrees =
      glm::degrees(2 * std::atan(std::tan(half_x) * double(height) / double(width)));
  camera.near_plane = kSpawnNearPlane;
  return camera;
}

}  // namespace cdsim
