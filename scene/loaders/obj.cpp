#include "obj.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cfloat>
#include <climits>
#include <deque>
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

// One corner of a face: 0-based indices into the v and vt lines of the whole
// file (negative indices already resolved against the lines before the face);
// texcoord -1 when the corner has none. Positive indices are checked against
// the totals once the file is read.
struct ObjCorner {
  long long vertex = 0, texcoord = -1, normal = -1;
  std::string_view written;  // the corner as written, for messages
};

// A face as the file gives it, with its line and the material in force
// (an index into FilteredObj::material_names, -1 for none).
struct ObjFace {
  size_t line = 0;
  int material = -1;
  std::vector<ObjCorner> corners;
};

// What filter_obj hands on: the text tinyobjloader reads (vertices, texture
// coordinates, normals, materials; no faces), and the faces, which cdsim
// reads itself: tinyobjloader keeps no line numbers, stores a face's corner
// count in an unsigned char (so at most 255 corners), and resolves a negative
// index past the start to -1 without a word.
struct FilteredObj {
  std::string text;
  std::vector<ObjFace> faces;
  std::vector<std::string> material_names;
  // Lines joined at a '\' continuation: the corners of their faces point
  // into them (a deque never moves its elements), the others into the text.
  std::deque<std::string> joined_lines;
  size_t dropped = 0;
  size_t positions = 0, texcoords = 0, normals = 0;
};

// tinyobjloader reads every number with its own parser, which takes garbage
// as 0 and a prefix as the whole ("1.5abc" is 1.5), and stores floats. So
// every number of the lines it uses is checked here first: decimal, the whole
// word, finite and within the range of a float; every face corner a non-zero
// integer index in one of the forms v, v/vt, v//vn, v/vt/vn, a negative one
// no further back than the lines before it.
void check_obj_line(std::string_view directive, const std::vector<std::string_view>& words,
                    const std::string& name, size_t line_number, const FilteredObj& so_far,
                    ObjFace* face) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("{}:{}: '{}' {}", name, line_number, directive, what));
  };
  if (directive == "f") {
    if (words.empty()) fail("has no corners");
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
      long long index[3] = {0, 0, 0};
      for (size_t i = 0; ok && i < parts.size(); ++i) {
        if (parts[i].empty() && i == 1 && parts.size() == 3) continue;  // v//vn
        const std::optional<long long> value = parse_integer(parts[i]);
        ok = value && *value != 0 && *value >= INT_MIN && *value <= INT_MAX;
        if (ok) index[i] = *value;
      }
      if (!ok)
        fail(fmt::format("corner {}: {} is not a vertex reference (v, v/vt, v//vn or v/vt/vn, each "
                         "a non-zero integer)",
                         k + 1, quote_bytes(corner)));
      // A negative index counts back from the face: -1 is the last line before it.
      const size_t before[3] = {so_far.positions, so_far.texcoords, so_far.normals};
      const char* const kind[3] = {"vertex", "texture coordinate", "normal"};
      const char* const lines[3] = {"v", "vt", "vn"};
      for (size_t i = 0; i < 3; ++i)
        if (index[i] < 0 && size_t(-index[i]) > before[i])
          fail(fmt::format("corner {}: {} refers to {} {}, before the first: only {} '{}' lines "
                           "precede this line (a negative index counts back from the face)",
                           k + 1, quote_bytes(corner), kind[i], index[i], before[i], lines[i]));
      ObjCorner c;
      c.vertex = index[0] < 0 ? (long long)before[0] + index[0] : index[0] - 1;
      c.texcoord = index[1] == 0 ? -1 : index[1] < 0 ? (long long)before[1] + index[1] : index[1] - 1;
      c.normal = index[2] == 0 ? -1 : index[2] < 0 ? (long long)before[2] + index[2] : index[2] - 1;
      c.written = corner;
      face->corners.push_back(c);
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
// groups, smoothing and materials; faces are taken out (FilteredObj), and
// every other line (vw, vp, l, p, curv, ...) becomes empty so that line
// numbers stay the same (every line end becomes \n). A line ending in '\'
// continues on the next (the OBJ format's line continuation): the lines are
// joined, numbered by the first, and the continuation lines left empty. The
// v, vt, vn and f lines are checked (check_obj_line) and passed on without
// comments.
// `text` must outlive the result, whose faces point into it.
FilteredObj filter_obj(std::string_view text, const std::string& name) {
  static const std::set<std::string, std::less<>> kept = {"v", "vt", "vn", "o", "g", "s", "usemtl", "mtllib"};
  static const std::set<std::string, std::less<>> checked = {"v", "vt", "vn", "f"};
  text = without_utf8_bom(text);
  FilteredObj out;
  out.text.reserve(text.size());
  size_t line_number = 0;
  int material = -1;
  std::vector<std::string_view> words;
  std::string joined;
  for (size_t start = 0; start < text.size();) {
    // Lines end as tinyobjloader ends them: at \n, \r\n or a lone \r, so
    // that a directive after a lone \r is filtered as the line it is there.
    const auto next_line = [&] {
      size_t end = text.find_first_of("\r\n", start);
      if (end == std::string_view::npos) end = text.size();
      const std::string_view line = text.substr(start, end - start);
      start = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
      return line;
    };
    std::string_view line = next_line();
    ++line_number;
    const size_t first_line = line_number;
    size_t continued = 0;
    // Continued when the text before any comment ends in a backslash
    // (blanks after it aside): one inside a comment does not swallow the
    // next line.
    const auto continuation = [](std::string_view l) {
      l = l.substr(0, l.find('#'));
      const size_t last = l.find_last_not_of(" \t");
      return last != std::string_view::npos && l[last] == '\\' ? last : std::string_view::npos;
    };
    if (continuation(line) != std::string_view::npos) {
      joined.clear();
      for (size_t at; (at = continuation(line)) != std::string_view::npos;) {
        joined.append(line.substr(0, at));
        joined += ' ';
        if (start >= text.size()) {
          line = {};
          break;
        }
        line = next_line();
        ++line_number;
        ++continued;
      }
      joined.append(line);
      out.joined_lines.push_back(joined);
      line = out.joined_lines.back();
    }
    const size_t first = line.find_first_not_of(" \t\r");
    const size_t last = first == std::string_view::npos ? first : line.find_first_of(" \t\r", first);
    const std::string_view directive =
        first == std::string_view::npos ? std::string_view() : line.substr(first, last - first);
    std::string_view data = line.substr(last == std::string_view::npos ? line.size() : last);
    data = data.substr(0, data.find('#'));
    if (directive.empty() || directive[0] == '#') {
      out.text += '\n';
    } else if (checked.count(directive)) {
      check_exponents(std::string(line), name, first_line);
      if (directive == "f") {
        ObjFace face;
        face.line = first_line;
        face.material = material;
        words.clear();
        for_each_word(data, [&](std::string_view word) { words.push_back(word); });
        check_obj_line(directive, words, name, first_line, out, &face);
        out.faces.push_back(std::move(face));
        out.text += '\n';
      } else {
        words.clear();
        for_each_word(data, [&](std::string_view word) { words.push_back(word); });
        check_obj_line(directive, words, name, first_line, out, nullptr);
        (directive == "v" ? out.positions : directive == "vt" ? out.texcoords : out.normals) += 1;
        out.text += directive;
        for (const std::string_view word : words) {
          out.text += ' ';
          out.text += word;
        }
        out.text += '\n';
      }
    } else if (kept.count(directive)) {
      check_exponents(std::string(line), name, first_line);
      if (directive == "usemtl") {
        // The material's name is its first word, as tinyobjloader reads it.
        std::string material_name;
        for_each_word(data, [&](std::string_view word) {
          if (material_name.empty()) material_name = std::string(word);
        });
        out.material_names.push_back(material_name);
        material = int(out.material_names.size()) - 1;
      }
      out.text += line;
      out.text += '\n';
    } else {
      ++out.dropped;
      out.text += '\n';
    }
    out.text.append(continued, '\n');
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
                        const ImageLookup& lookup,
                        const std::optional<glm::dvec2>& missing_texcoord) {
  const FilteredObj filtered = filter_obj(text, name);
  std::istringstream obj(filtered.text);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &obj,
                                   &materials_reader, /*triangulate=*/false);
  while (!err.empty() && err.back() == '\n') err.pop_back();
  if (!ok) throw InputError(fmt::format("{}: not a readable OBJ file: {}", name, err));
  const size_t positions = attrib.vertices.size() / 3, texcoords = attrib.texcoords.size() / 2,
               normals = attrib.normals.size() / 3;
  // Negative indices were resolved against filter_obj's counts.
  if (positions != filtered.positions || texcoords != filtered.texcoords)
    throw InputError(fmt::format("{}: tinyobjloader read {} v and {} vt lines where cdsim counted "
                                 "{} and {}",
                                 name, positions, texcoords, filtered.positions,
                                 filtered.texcoords));

  std::vector<glm::ivec2> material_size;
  size_t sized = 0;
  for (const tinyobj::material_t& m : materials) {
    std::optional<glm::ivec2> size;
    if (lookup && !m.diffuse_texname.empty()) size = lookup(m.diffuse_texname);
    sized += size.has_value();
    material_size.push_back(size.value_or(default_texture_size));
  }
  // usemtl names to sizes; the first material of a name wins, as in tinyobjloader.
  std::vector<glm::ivec2> used_size;
  for (const std::string& used : filtered.material_names) {
    glm::ivec2 size = default_texture_size;
    for (size_t m = 0; m < materials.size(); ++m)
      if (materials[m].name == used) {
        size = material_size[m];
        break;
      }
    used_size.push_back(size);
  }

  MeshBuilder builder(name);
  size_t skipped = 0, defaulted = 0;
  for (const ObjFace& face : filtered.faces) {
    const auto fail = [&](size_t k, const std::string& what) {
      throw InputError(fmt::format("{}:{}: 'f' corner {}: {} {}", name, face.line, k + 1,
                                   quote_bytes(face.corners[k].written), what));
    };
    const size_t corners = face.corners.size();
    for (size_t k = 0; k < corners; ++k) {
      const ObjCorner& corner = face.corners[k];
      if (size_t(corner.vertex) >= positions)
        fail(k, fmt::format("refers to vertex {}, but the file has {} (v lines, counted from 1)",
                            corner.vertex + 1, positions));
      if (corner.texcoord >= 0 && size_t(corner.texcoord) >= texcoords)
        fail(k, fmt::format("refers to texture coordinate {}, but the file has {} (vt lines, "
                            "counted from 1)",
                            corner.texcoord + 1, texcoords));
      // Normals are not used, but an index past them is a broken file all the same.
      if (corner.normal >= 0 && size_t(corner.normal) >= normals)
        fail(k, fmt::format("refers to normal {}, but the file has {} (vn lines, counted from 1)",
                            corner.normal + 1, normals));
    }
    if (corners < 3) {
      ++skipped;
      continue;
    }
    const glm::ivec2 texture = face.material < 0 ? default_texture_size : used_size[size_t(face.material)];
    std::vector<MeshVertex> polygon;
    polygon.reserve(corners);
    for (size_t k = 0; k < corners; ++k) {
      const ObjCorner& corner = face.corners[k];
      MeshVertex v;
      const size_t p = 3 * size_t(corner.vertex);
      v.position = {attrib.vertices[p], attrib.vertices[p + 1], attrib.vertices[p + 2]};
      if (corner.texcoord >= 0) {
        const size_t t = 2 * size_t(corner.texcoord);
        // OBJ's t runs up the image; the unit's v runs down it, as in glTF.
        v.texcoord = {attrib.texcoords[t], 1.0 - double(attrib.texcoords[t + 1])};
      } else if (missing_texcoord) {
        v.texcoord = *missing_texcoord;
        ++defaulted;
      } else {
        fail(k, "has no texture coordinate (v/vt or v/vt/vn); every corner of a face needs one, "
                "or a scene file's \"missing_texcoord\": [s, t] to stand for the missing ones");
      }
      polygon.push_back(v);
    }
    const auto where = [&] { return fmt::format("face at line {}", face.line); };
    for (size_t k = 1; k + 1 < polygon.size(); ++k)
      builder.add(polygon[0], polygon[k], polygon[k + 1], texture, where);
  }
  while (!warn.empty() && warn.back() == '\n') warn.pop_back();
  for (char& c : warn)
    if (c == '\n') c = ';';
  LoadedObj out;
  out.summary = fmt::format("{} faces, {} triangles, {} materials ({} with a known texture size)",
                            filtered.faces.size(), builder.triangle_count(), materials.size(), sized);
  if (skipped) out.summary += fmt::format(", {} faces of fewer than 3 corners skipped", skipped);
  if (defaulted)
    out.summary += fmt::format(", {} corners without a texture coordinate given ({}, {})", defaulted,
                               missing_texcoord->x, missing_texcoord->y);
  if (filtered.dropped)
    out.summary += fmt::format(", {} lines of unused directives skipped", filtered.dropped);
  if (!warn.empty()) out.summary += "; tinyobjloader: " + warn;
  out.mesh = builder.take();
  return out;
}

}  // namespace

LoadedObj load_obj(const std::string& path, glm::ivec2 default_texture_size,
                   const std::optional<glm::dvec2>& missing_texcoord) {
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
                       default_texture_size, lookup, missing_texcoord);
}

LoadedObj load_obj_from_memory(const std::string& obj_text, const std::string& mtl_text,
                               const std::string& name, glm::ivec2 default_texture_size,
                               const std::optional<glm::dvec2>& missing_texcoord) {
  CheckedMaterialReader materials([&](const std::string&) { return std::optional<std::string>(mtl_text); });
  return load_obj_text(obj_text, materials, name, default_texture_size, {}, missing_texcoord);
}

}  // namespace cdsim
