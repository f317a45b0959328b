#include "cache_files.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

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
  return fs::temp_directory_path() / ("cdsim-" + name);
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
