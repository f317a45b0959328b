// Checks of a JSON text's structure that nlohmann::json cannot make for us,
// done without recursion so that they are safe on any input:
//
// - depth: nlohmann's parser is iterative, but everything after it recurses
//   once per level (dump(), tinygltf's conversion of `extras` and
//   `extensions`), so a file nested tens of thousands of levels deep overflows
//   the stack. check_json_depth refuses it first.
// - duplicate keys: nlohmann keeps the last of two equal keys in one object,
//   so a repeated field would silently override the first.
//
// Every JSON reader of an input file calls check_json_depth before parsing;
// readers of files cdsim writes itself (caches, shard results) may call it too.
#pragma once

#include <string>
#include <string_view>

#include "limits.hpp"

namespace cdsim {

// Throws InputError naming `name`, the line and the byte offset where arrays
// and objects first nest deeper than `max_depth`. Any text is accepted:
// strings (with their escapes) are skipped, and malformed JSON is left to the
// parser that follows.
void check_json_depth(std::string_view text, const std::string& name,
                      int max_depth = limits::kMaxJsonDepth);

// Throws InputError naming `name`, the line, the key's path (e.g.
// 'camera.eye' or 'nodes[2].name') and the line of its first occurrence when
// one object holds the same key twice (compared after unescaping, as the
// parser compares them). `text` must be JSON that has already parsed.
void check_json_unique_keys(std::string_view text, const std::string& name);

}  // namespace cdsim
