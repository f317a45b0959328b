// Files of cdsim's caches and outputs (cdsim area, cdsim regress --set, and
// every file a command writes): a stable content hash for cache keys,
// whole-file reads, writes that never leave half a file under the final name,
// and a lock that keeps two runs out of one output folder.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cdsim {

// FNV-1a, 64 bits: stable across runs and machines, unlike std::hash.
inline uint64_t fnv1a(std::string_view text, uint64_t hash = 1469598103934665603ull) {
  for (unsigned char c : text) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

// Throws std::runtime_error naming the file.
std::string read_text_file(const std::filesystem::path& path);
// Writes a temporary file in the same folder (.NAME.PID.N.tmp), flushes it to
// disk and renames it to path, so that path holds either its old content or
// all of the new. A path that exists and is not a regular file (/dev/stdout,
// /dev/full, a pipe) is written in place. Every failure (missing folder,
// permission, full disk) throws std::runtime_error with the path and
// strerror, and removes the temporary file.
void write_file_atomic(const std::filesystem::path& path, const std::string& text);
// The same for several files: all are written first, then all renamed, so a
// failure in any leaves every one as it was.
void write_files_atomic(const std::vector<std::pair<std::filesystem::path, std::string>>& files);
// $XDG_CACHE_HOME/cdsim/<name>, else ~/.cache/cdsim/<name>, else a temporary folder.
std::filesystem::path cache_root(const std::string& name);

// Creates an output folder (an --out) and its parents; throws
// std::runtime_error "--out FOLDER: cannot create the folder: REASON".
void create_output_folder(const std::filesystem::path& folder);

// An exclusive flock(2) on FOLDER/.cdsim.lock, held while the object lives
// (the kernel drops it when the process ends, however it ends). A second run
// on the same folder throws std::runtime_error naming the folder at once
// instead of waiting. The lock file itself stays.
class OutputFolderLock {
 public:
  explicit OutputFolderLock(const std::filesystem::path& folder);
  ~OutputFolderLock();
  OutputFolderLock(const OutputFolderLock&) = delete;
  OutputFolderLock& operator=(const OutputFolderLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace cdsim
