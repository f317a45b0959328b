#include "obj.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cfloat>
#include <climits>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <string_view>
#include <tuple>

#include "file_io.hpp"
#include "image_size.hpp"
#include "mesh_builder.hpp"
#include "strict_text.hpp"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#endif
#include <tiny_obj_loader.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace cdsim {

namespace {

using ImageLookup = std::function<std::optional<glm::ivec2>(const std::string& texture_name)>;

// The largest magnitude of an OBJ number: tinyobjloader stores floats.
constexpr double kObjNumberLimit = FLT_MAX;

// tinyobjloader 2.0.0rc10 has undefined behaviour on two inputs the fuzzer
// found: a number whose exponent has 10 digits overflows an int in
// tryParseDouble, and a huge joint id on a `vw` line overflows a float-to-int
// conversion. Exponents are therefore checked here first (a real exponent
// never needs more than 4 digits), and only the directives cdsim uses reach
// tinyobjloader.
void check_exponents(const std::string& line, const std::string& name, size_t line_number) {
  for (size_t i = 1; i < line.size(); ++i) {
    if ((line[i] != 'e' && line[i] != 'E') ||
        !(std::isdigit(static_cast<unsigned char>(line[i - 1])) || line[i - 1] == '.'))
      continue;
    size_t j = i + 1;
    if (j < line.size() && (line[j] == '+' || line[j] == '-')) ++j;
    size_t digits = 0;
    while (j + digits < line.size() && std::isdigit(static_cast<unsigned char>(line[j + digits])))
      ++digits;
    if (digits > 6)
      throw InputError(fmt::format("{}:{}: a number has an exponent of {} digits", name,
                                   line_number, digits));
  }
}

// tinyobjloader reads every number with its own parser, which takes garbage
// as 0 and a prefix as the whole ("1.5abc" is 1.5), and stores floats. So
// every number of the lines it uses is checked here first: decimal, the whole
// word, finite and within the range of a float; every face corner a non-zero
// integer index in one of the forms v, v/vt, v//vn, v/vt/vn.
void check_obj_line(std::string_view directive, const std::vector<std::string_view>& words,
                    const std::string& name, size_t line_number) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}:{}: '{}' {}", name, line_number, directive, what));
  };
  if (directive == "f") {
    if (words.empty()) fail("has no corners");
    if (words.size() > 255)
      fail(fmt::format("has {} corners; a face may have at most 255", words.size()));
    for (size_t k = 0; k < words.size(); ++k) {
      const std::string_view corner = words[k];
      std::vector<std::string_view> parts;
      for (size_t start = 0;;) {
        const size_t slash = corner.find('/', start);
        parts.push_back(corner.substr(start, slash == std::string_view::npos ? slash : slash - start));
        if (slash == std::string_view::npos) break;
        start = slash + 1;
      }
      bool ok = parts.size() <= 3;
      for (size_t i = 0; ok && i < parts.size(); ++i) {
        if (parts[i].empty() && i == 1 && parts.size() == 3) continue;  // v//vn
        const std::optional<long long> index = parse_integer(parts[i]);
        ok = index && *index != 0 && *index >= INT_MIN && *index <= INT_MAX;
      }
      if (!ok)
        fail(fmt::format("corner {}: {} is not a vertex reference (v, v/vt, v//vn or v/vt/vn, each "
                         "a non-zero integer)",
                         k + 1, quote_bytes(corner)));
    }
    return;
  }
  const auto [fewest, most, form] =
      directive == "v"    ? std::make_tuple(size_t(3), size_t(7), "x y z [w] [r g b]")
      : directive == "vt" ? std::make_tuple(size_t(1), size_t(3), "u [v [w]]")
                          : std::make_tuple(size_t(3), size_t(3), "x y z");
  if (words.size() < fewest || words.size() > most)
    fail(fmt::format("expects {} ({}{} numbers), found {}", form, fewest,
                     most > fewest ? fmt::format(" to {}", most) : std::string(), words.size()));
  for (size_t i = 0; i < words.size(); ++i) {
    const ParsedNumber parsed = parse_number(words[i], kObjNumberLimit);
    if (!parsed.ok())
      fail(fmt::format("number {}: {}{}", i + 1, number_problem(parsed, words[i]),
                       parsed.problem == NumberProblem::kOutOfRange
                           ? " (tinyobjloader stores OBJ numbers as floats)"
                           : ""));
  }
}

// The OBJ text tinyobjloader sees: vertices, texture coordinates, normals,
// faces, groups, smoothing and materials; every other line (vw, vp, l, p,
// curv, ...) becomes empty so that line numbers stay the same (every line
// end becomes \n). The v, vt, vn
// and f lines are checked (check_obj_line) and passed on without comments.
std::string filter_obj(std::string_view text, const std::string& name, size_t* dropped) {
  static const std::set<std::string, std::less<>> kept = {"v", "vt", "vn", "f", "o", "g", "s", "usemtl", "mtllib"};
  static const std::set<std::string, std::less<>> checked = {"v", "vt", "vn", "f"};
  text = without_utf8_bom(text);
  std::string out;
  out.reserve(text.size());
  size_t line_number = 0;
  std::vector<std::string_view> words;
  for (size_t start = 0; start < text.size();) {
    // Lines end as tinyobjloader ends them: at \n, \r\n or a lone \r, so
    // that a directive after a lone \r is filtered as the line it is there.
    size_t end = text.find_first_of("\r\n", start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(start, end - start);
    start = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
    ++line_number;
    const size_t first = line.find_first_not_of(" \t\r");
    const size_t last = first == std::string_view::npos ? first : line.find_first_of(" \t\r", first);
    const std::string_view directive =
        first == std::string_view::npos ? std::string_view() : line.substr(first, last - first);
    if (directive.empty() || directive[0] == '#') {
      out += '\n';
    } else if (checked.count(directive)) {
      check_exponents(std::string(line), name, line_number);
      std::string_view data = line.substr(last == std::string_view::npos ? line.size() : last);
      data = data.substr(0, data.find('#'));
      words.clear();
      for_each_word(data, [&](std::string_view word) { words.push_back(word); });
      check_obj_line(directive, words, name, line_number);
      out += directive;
      for (const std::string_view word : words) {
        out += ' ';
        out += word;
      }
      out += '\n';
    } else if (kept.count(directive)) {
      check_exponents(std::string(line), name, line_number);
      out += line;
      out += '\n';
    } else {
      ++*dropped;
      out += '\n';
    }
  }
  return out;
}

// Material libraries through the same exponent check, from files beside the
// .obj (with the size cap) or from one text in memory.
class CheckedMaterialReader : public tinyobj::MaterialReader {
 public:
  using Source = std::function<std::optional<std::string>(const std::string& library)>;
  explicit CheckedMaterialReader(Source source) : source_(std::move(source)) {}

  bool operator()(const std::string& library, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* material_map, std::string* warn,
                  std::string* err) override {
    const std::optional<std::string> text = source_(library);
    if (!text) {
      if (warn) *warn += fmt::format("material library '{}' not found\n", library);
      return false;
    }
    size_t line_number = 0;
    for (size_t start = 0; start < text->size();) {
      size_t end = text->find('\n', start);
      if (end == std::string::npos) end = text->size();
      check_exponents(text->substr(start, end - start), library, ++line_number);
      start = end + 1;
    }
    std::istringstream stream{std::string(without_utf8_bom(*text))};
    tinyobj::LoadMtl(material_map, materials, &stream, warn, err);
    return true;
  }

 private:
  Source source_;
};

LoadedObj load_obj_text(const std::string& text, tinyobj::MaterialReader& materials_reader,
                        const std::string& name, glm::ivec2 default_texture_size,
                        const ImageLookup& lookup) {
  size_t dropped = 0;
  std::istringstream obj(filter_obj(text, name, &dropped));
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &obj,
                                   &materials_reader, /*triangulate=*/false);
  while (!err.empty() && err.back() == '\n') err.pop_back();
  if (!ok) throw InputError(fmt::format("{}: not a readable OBJ file: {}", name, err));

  std::vector<glm::ivec2> material_size;
  size_t sized = 0;
  for (const tinyobj::material_t& m : materials) {
    std::optional<glm::ivec2> size;
    if (lookup && !m.diffuse_texname.empty()) size = lookup(m.diffuse_texname);
    sized += size.has_value();
    material_size.push_back(size.value_or(default_texture_size));
  }

  const size_t positions = attrib.vertices.size() / 3, texcoords = attrib.texcoords.size() / 2;
  MeshBuilder builder(name);
  size_t faces = 0, skipped = 0;
  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    size_t offset = 0;
    for (size_t face = 0; face < mesh.num_face_vertices.size(); ++face) {
      const size_t corners = mesh.num_face_vertices[face];
      const auto where = [&] { return fmt::format("object {} face {}", quote_bytes(shape.name), face); };
      if (offset + corners > mesh.indices.size())
        throw InputError(fmt::format("{}: {}: the face's {} corners run past the {} indices read "
                                     "(a face may have at most 255 corners)",
                                     name, where(), corners, mesh.indices.size()));
      ++faces;
      if (corners < 3) {
        ++skipped;
        offset += corners;
        continue;
      }
      glm::ivec2 texture = default_texture_size;
      if (face < mesh.material_ids.size()) {
        const int material = mesh.material_ids[face];
        if (material >= int(material_size.size()))
          throw InputError(fmt::format("{}: {}: material {} is outside the {} materials", name,
                                       where(), material, material_size.size()));
        if (material >= 0) texture = material_size[size_t(material)];
      }
      std::vector<MeshVertex> polygon;
      for (size_t k = 0; k < corners; ++k) {
        const tinyobj::index_t index = mesh.indices[offset + k];
        if (index.vertex_index < 0 || size_t(index.vertex_index) >= positions)
          throw InputError(fmt::format("{}: {}: corner {} refers to vertex {}, but the file has {} "
                                       "(v lines, counted from 1)",
                                       name, where(), k, index.vertex_index + 1, positions));
        if (index.texcoord_index >= 0 && size_t(index.texcoord_index) >= texcoords)
          throw InputError(fmt::format("{}: {}: corner {} refers to texture coordinate {}, but the "
                                       "file has {} (vt lines, counted from 1)",
                                       name, where(), k, index.texcoord_index + 1, texcoords));
        MeshVertex v;
        const size_t p = 3 * size_t(index.vertex_index);
        v.position = {attrib.vertices[p], attrib.vertices[p + 1], attrib.vertices[p + 2]};
        if (index.texcoord_index >= 0) {
          const size_t t = 2 * size_t(index.texcoord_index);
          // OBJ's t runs up the image; the unit's v runs down it, as in glTF.
          v.texcoord = {attrib.texcoords[t], 1.0 - double(attrib.texcoords[t + 1])};
        }
        polygon.push_back(v);
      }
      offset += corners;
      for (size_t k = 1; k + 1 < polygon.size(); ++k)
        builder.add(polygon[0], polygon[k], polygon[k + 1], texture, where);
    }
  }
  while (!warn.empty() && warn.back() == '\n') warn.pop_back();
  for (char& c : warn)
    if (c == '\n') c = ';';
  LoadedObj out;
  out.summary = fmt::format("{} faces, {} triangles, {} materials ({} with a known texture size)",
                            faces, builder.triangle_count(), materials.size(), sized);
  if (skipped) out.summary += fmt::format(", {} faces of fewer than 3 corners skipped", skipped);
  if (dropped) out.summary += fmt::format(", {} lines of unused directives skipped", dropped);
  if (!warn.empty()) out.summary += "; tinyobjloader: " + warn;
  out.mesh = builder.take();
  return out;
}

}  // namespace

LoadedObj load_obj(const std::string& path, glm::ivec2 default_texture_size) {
  const std::vector<uint8_t> bytes = read_file_bytes(path);
  CheckedMaterialReader materials([&](const std::string& library) -> std::optional<std::string> {
    const std::string mtl_path = resolve_relative(path, library);
    if (!std::ifstream(mtl_path)) return std::nullopt;
    const std::vector<uint8_t> mtl = read_file_bytes(mtl_path);
    return std::string(mtl.begin(), mtl.end());
  });
  const ImageLookup lookup = [&](const std::string& texture) {
    return image_size_from_file(resolve_relative(path, texture));
  };
  return load_obj_text(std::string(bytes.begin(), bytes.end()), materials, path,
                       default_texture_size, lookup);
}

LoadedObj load_obj_from_memory(const std::string& obj_text, const std::string& mtl_text,
                               const std::string& name, glm::ivec2 default_texture_size) {
  CheckedMaterialReader materials([&](const std::string&) { return std::optional<std::string>(mtl_text); });
  return load_obj_text(obj_text, materials, name, default_texture_size, {});
}

}  // namespace cdsim
