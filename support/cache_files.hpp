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
// The per-user cache folder of cdsim area ("area") and the RTL cache ("rtl"):
// $XDG_CACHE_HOME/cdsim/<name>, else $HOME/.cache/cdsim/<name>, else
// .cache/cdsim/<name> in the home folder that the password database gives
// this user. Never a folder shared between users: with none of the three it
// throws, asking for --cache / --rtl-cache.
std::filesystem::path cache_root(const std::string& name);
// Before a cache folder is used (read or written): creates it and its missing
// parents with mode 0700, then checks that it is a folder, owned by this user
// and writable by no one else, since cdsim loads code (the RTL's bench-*.so)
// and results from it. Throws std::runtime_error naming `option`, the folder
// and the fix otherwise.
void check_cache_folder(const std::filesystem::path& folder, const std::string& option);

// The record of a cache entry's files, written when the entry is built and
// checked before it is used: one line "SIZE HASH NAME" a file, NAME relative
// to `base`, HASH FNV-1a 64 of the content. A file that a full disk or a
// killed copy truncated, or that anything changed, fails the check.
void write_manifest(const std::filesystem::path& manifest, const std::filesystem::path& base,
                    const std::vector<std::filesystem::path>& files);
// "" when the manifest exists, parses, and every file it lists matches;
// otherwise what is wrong ("bench.so: 1000 bytes, 8016232 when built").
std::string verify_manifest(const std::filesystem::path& manifest, const std::filesystem::path& base);
// Every regular file under folder, recursively, in name order.
std::vector<std::filesystem::path> files_under(const std::filesystem::path& folder);

// An exclusive flock(2) on a cache entry's lock file, held while the object
// lives: a second cdsim that wants the same entry waits (saying once, on
// stderr, what it waits for) instead of building it twice. SIGINT or SIGTERM
// while waiting throws Interrupted.
class CacheEntryLock {
 public:
  CacheEntryLock(const std::filesystem::path& lock_file, const std::string& what);
  ~CacheEntryLock();
  CacheEntryLock(const CacheEntryLock&) = delete;
  CacheEntryLock& operator=(const CacheEntryLock&) = delete;

 private:
  int fd_ = -1;
};

// Removes a work folder (a cache entry being built) when the scope ends
// without release(): a failed or interrupted build leaves nothing behind.
class RemoveOnExit {
 public:
  explicit RemoveOnExit(std::filesystem::path folder) : folder_(std::move(folder)) {}
  ~RemoveOnExit();
  RemoveOnExit(const RemoveOnExit&) = delete;
  RemoveOnExit& operator=(const RemoveOnExit&) = delete;
  void release() { folder_.clear(); }

 private:
  std::filesystem::path folder_;
};

// One file a command reads or writes, with the option that names it.
struct NamedFile {
  std::string option;  // "--json", "--scene"
  std::filesystem::path path;
};
// Refuses, before any work, an output that is the same file as an input of
// the run or as another output, by filesystem identity (device and inode,
// so through symbolic and hard links, "./x" and "x"; for a file not yet
// there, its folder's identity and its name): `run --scene S.json --json
// S.json` would overwrite the scene, `--json F --dump F` lose one of them.
// Devices, pipes and sockets (/dev/null, /dev/stdout) are exempt: writing one
// replaces nothing. Throws std::invalid_argument naming both options and paths.
void check_distinct_files(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs);
// The file a scene name (--scene, choose's SCENE...) reads: none for
// "default" and "hard:NAME", the archive of "MAP.pk3:maps/x.bsp", else the name.
std::filesystem::path scene_input_file(const std::string& scene);
// An output that is refused unless it is, or will be, a regular file: an FST
// waveform is written by seeking, so a device, a pipe or a folder cannot
// hold it. Throws std::invalid_argument "OPTION PATH: is a character device;
// ..." for those.
void check_regular_output(const std::string& option, const std::filesystem::path& path);

// For a file that another library writes by name (the FST waveform): a
// temporary name beside path (beside its target, for a symbolic link), and
// the rename that puts the finished file in place, as write_file_atomic does;
// a failure throws naming path and removes the temporary file.
std::filesystem::path temporary_beside(const std::filesystem::path& path);
void publish_file(const std::filesystem::path& temporary, const std::filesystem::path& path);

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
