#include "cache_files.hpp"

#include <fmt/format.h>

#include <cstdlib>
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

void write_file_atomic(const fs::path& path, const std::string& text) {
  const fs::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary);
    out << text;
    out.close();
    if (!out) throw std::runtime_error(fmt::format("{}: cannot write", partial.string()));
  }
  std::error_code error;
  fs::rename(partial, path, error);
  if (error)
    throw std::runtime_error(fmt::format("{}: cannot write ({})", path.string(), error.message()));
}

fs::path cache_root(const std::string& name) {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "cdsim" / name;
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache/cdsim" / name;
  return fs::temp_directory_path() / ("cdsim-" + name);
}

}  // namespace cdsim
