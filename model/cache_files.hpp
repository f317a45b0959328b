// Files of cdsim's caches (cdsim area, cdsim regress --set): a stable content
// hash for cache keys, whole-file reads, and writes that never leave half a
// file under the final name.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace cdsim {

// FNV-1a, 64 bits: stable across runs and machines, unlike std::hash.
inline uint64_t fnv1a(std::string_view text, uint64_t hash = 1469598103934665603ull) {
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

// Throws std::runtime_error naming the file.
std::string read_text_file(const std::filesystem::path& path);
// Writes path.partial, then renames it to path.
void write_file_atomic(const std::filesystem::path& path, const std::string& text);
// $XDG_CACHE_HOME/cdsim/<name>, else ~/.cache/cdsim/<name>, else a temporary folder.
std::filesystem::path cache_root(const std::string& name);

}  // namespace cdsim
