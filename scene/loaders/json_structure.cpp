#include "json_structure.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <map>
#include <vector>

#include "strict_text.hpp"
#include "triangle.hpp"

namespace cdsim {

namespace {

// The end of the string whose opening quote is at `open`: the index after its
// closing quote, or text.size() when it is not closed.
size_t skip_string(std::string_view text, size_t open, size_t* lines) {
  for (size_t i = open + 1; i < text.size(); ++i) {
    if (text[i] == '\\') {
      ++i;
    } else if (text[i] == '"') {
      return i + 1;
    } else if (text[i] == '\n') {
      ++*lines;  // not JSON, but the parser will say so; keep the count true
    }
  }
  return text.size();
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Four hex digits at `at`, or -1.
long hex4(std::string_view text, size_t at) {
  if (at + 4 > text.size()) return -1;
  long value = 0;
  for (size_t k = 0; k < 4; ++k) {
    const int digit = hex_value(text[at + k]);
    if (digit < 0) return -1;
    value = value * 16 + digit;
  }
  return value;
}

void append_utf8(std::string& out, uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

// The string whose opening quote is at `open`, unescaped as the parser
// unescapes it, so that "a" and "\u0061" are the same key; *end is set past
// the closing quote.
std::string unescape_string(std::string_view text, size_t open, size_t* end) {
  std::string out;
  size_t i = open + 1;
  while (i < text.size() && text[i] != '"') {
    if (text[i] != '\\' || i + 1 >= text.size()) {
      out += text[i++];
      continue;
    }
    const char escaped = text[i + 1];
    i += 2;
    switch (escaped) {
      case 'b': out += '\b'; break;
      case 'f': out += '\f'; break;
      case 'n': out += '\n'; break;
      case 'r': out += '\r'; break;
      case 't': out += '\t'; break;
      case 'u': {
        long code = hex4(text, i);
        if (code < 0) break;
        i += 4;
        if (code >= 0xD800 && code < 0xDC00 && i + 1 < text.size() && text[i] == '\\' &&
            text[i + 1] == 'u') {
          const long low = hex4(text, i + 2);
          if (low >= 0xDC00 && low < 0xE000) {
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
            i += 6;
          }
        }
        append_utf8(out, static_cast<uint32_t>(code));
        break;
      }
      default: out += escaped; break;  // \" \\ \/
    }
  }
  *end = i < text.size() ? i + 1 : text.size();
  return out;
}

}  // namespace

void check_json_depth(std::string_view text, const std::string& name, int max_depth) {
  int depth = 0;
  size_t line = 1;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '"') {
      i = skip_string(text, i, &line);
      continue;
    }
    if (c == '\n') {
      ++line;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        throw InputError(fmt::format(
            "{}:{}: JSON nested deeper than {} levels (arrays and objects inside one another) at "
            "byte {}; deeper nesting is refused before parsing",
            name, line, max_depth, i));
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
    ++i;
  }
}

void check_json_unique_keys(std::string_view text, const std::string& name) {
  struct Frame {
    bool object = false;
    bool expect_key = false;
    size_t index = 0;                   // arrays: the element being read
    std::string key;                    // objects: the key being read
    std::map<std::string, size_t> seen;  // objects: key -> its line
  };
  std::vector<Frame> stack;
  // 'camera.eye', 'nodes[2].name': where a key stands, for the message.
  const auto path_to = [&](const std::string& key) {
    std::string path;
    for (size_t level = 0; level + 1 < stack.size(); ++level) {
      const Frame& f = stack[level];
      if (f.object)
        path += (path.empty() ? "" : ".") + f.key;
      else
        path += fmt::format("[{}]", f.index);
    }
    return path + (path.empty() ? "" : ".") + key;
  };
  size_t line = 1;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '"') {
      if (!stack.empty() && stack.back().object && stack.back().expect_key) {
        Frame& frame = stack.back();
        size_t end = 0;
        std::string key = unescape_string(text, i, &end);
        const auto [it, inserted] = frame.seen.emplace(key, line);
        if (!inserted)
          throw InputError(fmt::format(
              "{}:{}: field {} appears twice in one object (first at line {}); JSON leaves the "
              "meaning of a repeated key open, so it is refused",
              name, line, quote_bytes(path_to(key), 80), it->second));
        frame.key = std::move(key);
        frame.expect_key = false;
        i = end;
      } else {
        i = skip_string(text, i, &line);
      }
      continue;
    }
    if (c == '\n') {
      ++line;
    } else if (c == '{' || c == '[') {
      Frame frame;
      frame.object = c == '{';
      frame.expect_key = frame.object;
      stack.push_back(std::move(frame));
    } else if ((c == '}' || c == ']') && !stack.empty()) {
      stack.pop_back();
    } else if (c == ',' && !stack.empty()) {
      if (stack.back().object)
        stack.back().expect_key = true;
      else
        ++stack.back().index;
    }
    ++i;
  }
}

}  // namespace cdsim
