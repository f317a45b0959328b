#include "cache_files.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <pwd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <iostream>
#include <thread>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "interrupt.hpp"

namespace cdsim {

namespace fs = std::filesystem;

std::string read_text_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot read", path.string()));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

namespace {

[[noreturn]] void fail(const fs::path& path, const char* what, int error) {
  throw std::runtime_error(fmt::format("{}: {}: {}", path.string(), what, std::strerror(error)));
}

// Writes all of text to fd; returns 0 or the errno of the failure.
int write_all(int fd, const std::string& text) {
  const char* at = text.data();
  size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, at, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    at += n;
    left -= size_t(n);
  }
  return 0;
}

// A path that exists and is not a regular file or a symbolic link to one.
bool is_special(const fs::path& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

void write_in_place(const fs::path& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot open for writing", errno);
  int error = write_all(fd, text);
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error) fail(path, "cannot write", error);
}

struct Pending {
  fs::path path, temporary;
};

// The final name to rename onto: a symbolic link's target, so that the link stays.
fs::path final_name(const fs::path& path) {
  std::error_code ignored;
  if (fs::is_symlink(path, ignored)) {
    const fs::path target = fs::weakly_canonical(path, ignored);
    if (!ignored) return target;
  }
  return path;
}

Pending write_temporary(const fs::path& path, const std::string& text) {
  static std::atomic<unsigned> counter{0};
  Pending p;
  p.path = final_name(path);
  const fs::path folder = p.path.parent_path();
  p.temporary = folder / fmt::format(".{}.{}.{}.tmp", p.path.filename().string(), ::getpid(),
                                     counter++);
  const int fd = ::open(p.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    std::error_code ignored;
    if (error == ENOENT && !folder.empty() && !fs::is_directory(folder, ignored))
      throw std::runtime_error(fmt::format("{}: cannot write: the folder {} does not exist",
                                           path.string(), folder.string()));
    fail(path, "cannot write", error);
  }
  int error = write_all(fd, text);
  if (error == 0 && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error) {
    ::unlink(p.temporary.c_str());
    fail(path, "cannot write", error);
  }
  return p;
}

}  // namespace

void write_file_atomic(const fs::path& path, const std::string& text) {
  write_files_atomic({{path, text}});
}

void write_files_atomic(const std::vector<std::pair<fs::path, std::string>>& files) {
  std::vector<Pending> pending;
  try {
    for (const auto& [path, text] : files) {
      if (is_special(path)) {
        if (fs::is_directory(path)) fail(path, "cannot write", EISDIR);
        write_in_place(path, text);
      } else {
        pending.push_back(write_temporary(path, text));
      }
    }
  } catch (...) {
    for (const Pending& p : pending) ::unlink(p.temporary.c_str());
    throw;
  }
  for (size_t i = 0; i < pending.size(); ++i) {
    if (::rename(pending[i].temporary.c_str(), pending[i].path.c_str()) != 0) {
      const int error = errno;
      for (size_t j = i; j < pending.size(); ++j) ::unlink(pending[j].temporary.c_str());
      fail(pending[i].path, "cannot write", error);
    }
  }
}

fs::path cache_root(const std::string& name) {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "cdsim" / name;
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache/cdsim" / name;
  std::vector<char> buffer(16384);
  struct passwd entry, *found = nullptr;
  if (::getpwuid_r(::geteuid(), &entry, buffer.data(), buffer.size(), &found) == 0 && found &&
      found->pw_dir && found->pw_dir[0] == '/')
    return fs::path(found->pw_dir) / ".cache/cdsim" / name;
  throw std::runtime_error(fmt::format(
      "no cache folder for {}: XDG_CACHE_HOME and HOME are unset and user {} has no home folder; "
      "set one of them or give the folder ({})",
      name, ::geteuid(), name == "rtl" ? "--rtl-cache DIR" : "--cache DIR"));
}

void check_cache_folder(const fs::path& folder, const std::string& option) {
  // Missing parents too, each 0700: ~/.cache/cdsim is nobody else's business.
  std::vector<fs::path> missing;
  for (fs::path at = fs::absolute(folder); !at.empty(); at = at.parent_path()) {
    struct stat st;
    if (::lstat(at.c_str(), &st) == 0) break;
    missing.push_back(at);
    if (at == at.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it)
    if (::mkdir(it->c_str(), 0700) != 0 && errno != EEXIST)
      throw std::runtime_error(fmt::format("{} {}: cannot create the folder {}: {}", option, folder.string(),
                                           it->string(), std::strerror(errno)));
  struct stat st;
  if (::stat(folder.c_str(), &st) != 0)
    throw std::runtime_error(
        fmt::format("{} {}: cannot use the cache folder: {}", option, folder.string(), std::strerror(errno)));
  if (!S_ISDIR(st.st_mode))
    throw std::runtime_error(fmt::format("{} {}: the cache folder is not a folder", option, folder.string()));
  if (st.st_uid != ::geteuid())
    throw std::runtime_error(fmt::format(
        "{} {}: the cache folder belongs to user {}, not to you (user {}); cdsim loads code from "
        "its cache, so it uses only a folder of your own",
        option, folder.string(), st.st_uid, ::geteuid()));
  if (st.st_mode & (S_IWGRP | S_IWOTH))
    throw std::runtime_error(fmt::format(
        "{} {}: the cache folder is writable by {} (mode {:04o}); cdsim loads code from its cache, "
        "so it uses only a folder no one else can write: chmod go-w '{}'",
        option, folder.string(), st.st_mode & S_IWOTH ? "every user" : "its group", st.st_mode & 07777,
        folder.string()));
}

namespace {

struct Digest {
  uint64_t size = 0, hash = 0;
};

Digest digest_of(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail(path, "cannot read", errno);
  Digest d;
  d.hash = fnv1a("");
  std::vector<char> buffer(1 << 16);
  for (;;) {
    const ssize_t n = ::read(fd, buffer.data(), buffer.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int error = errno;
      ::close(fd);
      fail(path, "cannot read", error);
    }
    if (n == 0) break;
    d.hash = fnv1a(std::string_view(buffer.data(), size_t(n)), d.hash);
    d.size += uint64_t(n);
  }
  ::close(fd);
  return d;
}

}  // namespace

std::vector<fs::path> files_under(const fs::path& folder) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.is_regular_file()) out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

void write_manifest(const fs::path& manifest, const fs::path& base, const std::vector<fs::path>& files) {
  std::string text;
  for (const fs::path& file : files) {
    const Digest d = digest_of(file);
    text += fmt::format("{} {:016x} {}\n", d.size, d.hash, fs::relative(file, base).string());
  }
  write_file_atomic(manifest, text);
}

std::string verify_manifest(const fs::path& manifest, const fs::path& base) {
  std::ifstream in(manifest);
  if (!in) return fmt::format("{}: missing", manifest.filename().string());
  std::string line;
  int lines = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    uint64_t size = 0;
    std::string hash, name;
    if (!(fields >> size >> hash) || !std::getline(fields >> std::ws, name) || name.empty())
      return fmt::format("{}: line {} is not 'SIZE HASH NAME'", manifest.filename().string(), lines + 1);
    ++lines;
    const fs::path file = base / name;
    struct stat st;
    if (::stat(file.c_str(), &st) != 0) return fmt::format("{}: missing", name);
    if (!S_ISREG(st.st_mode)) return fmt::format("{}: not a regular file", name);
    if (uint64_t(st.st_size) != size)
      return fmt::format("{}: {} bytes, {} when built", name, st.st_size, size);
    if (fmt::format("{:016x}", digest_of(file).hash) != hash) return fmt::format("{}: its content changed since it was built", name);
  }
  if (lines == 0) return fmt::format("{}: empty", manifest.filename().string());
  return "";
}

CacheEntryLock::CacheEntryLock(const fs::path& lock_file, const std::string& what) {
  fd_ = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
  if (fd_ < 0) fail(lock_file, "cannot create the cache entry's lock file", errno);
  bool said = false;
  while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    if (error != EWOULDBLOCK && error != EINTR) {
      ::close(fd_);
      fail(lock_file, "cannot lock", error);
    }
    if (!said) {
      std::cerr << fmt::format("{}: waiting for another cdsim that builds it (it holds {})\n", what,
                               lock_file.string());
      said = true;
    }
    if (interrupted()) {
      ::close(fd_);
      throw_if_interrupted();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

CacheEntryLock::~CacheEntryLock() {
  if (fd_ >= 0) ::close(fd_);
}

RemoveOnExit::~RemoveOnExit() {
  if (folder_.empty()) return;
  std::error_code ignored;
  fs::remove_all(folder_, ignored);
}

namespace {

// Where a path leads: the file itself when it exists, else its folder and name.
struct Identity {
  bool exists = false, special = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string name;  // of a file not yet there; "" if its folder is missing too
};

Identity identity_of(const fs::path& path) {
  Identity id;
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.special = !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode);
    id.device = st.st_dev;
    id.inode = st.st_ino;
    return id;
  }
  std::error_code ec;
  const fs::path full = fs::weakly_canonical(fs::absolute(path, ec), ec);
  const fs::path folder = full.parent_path();
  if (!ec && ::stat(folder.c_str(), &st) == 0) {
    id.device = st.st_dev;
    id.inode = st.st_ino;
    id.name = full.filename().string();
  }
  return id;
}

bool same_file(const Identity& a, const Identity& b) {
  if (a.special || b.special || a.exists != b.exists) return false;
  if (!a.exists && (a.name.empty() || b.name.empty() || a.name != b.name)) return false;
  return a.device == b.device && a.inode == b.inode;
}

const char* kind_of(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a pipe";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISDIR(mode)) return "a folder";
  return "not a regular file";
}

}  // namespace

void check_distinct_files(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  std::vector<Identity> output_ids;
  for (const NamedFile& out : outputs) output_ids.push_back(out.path.empty() ? Identity{} : identity_of(out.path));
  for (size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].path.empty()) continue;
    for (const NamedFile& in : inputs)
      if (!in.path.empty() && same_file(output_ids[i], identity_of(in.path)))
        throw std::invalid_argument(fmt::format(
            "{} {}: is the input {} {}; cdsim does not overwrite what it reads: write elsewhere",
            outputs[i].option, outputs[i].path.string(), in.option, in.path.string()));
    for (size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && same_file(output_ids[i], output_ids[j]))
        throw std::invalid_argument(fmt::format(
            "{} {} and {} {}: both name one file, which would keep only one of them: give each its own",
            outputs[j].option, outputs[j].path.string(), outputs[i].option, outputs[i].path.string()));
  }
}

fs::path scene_input_file(const std::string& scene) {
  if (scene.empty() || scene == "default" || scene.rfind("hard:", 0) == 0) return {};
  std::error_code ec;
  if (fs::exists(scene, ec)) return scene;
  std::string lower = scene;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const size_t at = lower.find(".pk3:");
  return at == std::string::npos ? fs::path(scene) : fs::path(scene.substr(0, at + 4));
}

fs::path temporary_beside(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  const fs::path target = final_name(path);
  return target.parent_path() /
         fmt::format(".{}.{}.{}.tmp", target.filename().string(), ::getpid(), counter++);
}

void publish_file(const fs::path& temporary, const fs::path& path) {
  if (::rename(temporary.c_str(), final_name(path).c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    fail(path, "cannot write", error);
  }
}

void check_regular_output(const std::string& option, const fs::path& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw std::invalid_argument(fmt::format(
        "{} {}: is {}; it takes a regular file (cdsim writes it beside, then renames it over)",
        option, path.string(), kind_of(st.st_mode)));
}

void create_output_folder(const std::filesystem::path& folder) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error)
    throw std::runtime_error(
        fmt::format("--out {}: cannot create the folder: {}", folder.string(), error.message()));
}

OutputFolderLock::OutputFolderLock(const fs::path& folder) {
  const fs::path lock = folder / ".cdsim.lock";
  fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd_ < 0) fail(lock, "cannot create the folder's lock file", errno);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throw std::runtime_error(fmt::format(
          "{}: another cdsim run is writing into this folder (it holds {}); wait for it to end or "
          "choose another --out",
          folder.string(), lock.string()));
    fail(lock, "cannot lock", error);
  }
}

OutputFolderLock::~OutputFolderLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace cdsim
