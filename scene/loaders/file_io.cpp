#include "file_io.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <istream>
#include <memory>

#include "limits.hpp"
#include "triangle.hpp"

namespace cdsim {

void require_regular_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_type type = fs::status(path, error).type();
  if (type == fs::file_type::not_found || type == fs::file_type::none)
    throw InputError(fmt::format("{}: cannot open: {}", path,
                                 error ? error.message() : std::string(std::strerror(ENOENT))));
  if (type == fs::file_type::regular) return;
  const char* kind = type == fs::file_type::directory   ? "a directory"
                     : type == fs::file_type::character ? "a character device"
                     : type == fs::file_type::block     ? "a block device"
                     : type == fs::file_type::fifo      ? "a FIFO"
                     : type == fs::file_type::socket    ? "a socket"
                                                        : "of an unknown kind";
  throw InputError(fmt::format("{}: is {}, not a regular file", path, kind));
}

std::string too_large_message(const std::string& name) {
  return fmt::format("{}: larger than the {} MiB cap on input files", name,
                     limits::kMaxFileBytes >> 20);
}

std::vector<uint8_t> read_file_bytes(const std::string& path) {
  require_regular_file(path);
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > limits::kMaxFileBytes)
    throw InputError(fmt::format("{} ({} bytes)", too_large_message(path), size));
  const std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw InputError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  std::vector<uint8_t> bytes;
  uint8_t chunk[1 << 16];
  for (;;) {
    const size_t got = std::fread(chunk, 1, sizeof chunk, file.get());
    if (got == 0) break;
    // The file may grow after its size was taken.
    if (bytes.size() + got > limits::kMaxFileBytes) throw InputError(too_large_message(path));
    bytes.insert(bytes.end(), chunk, chunk + got);
  }
  if (std::ferror(file.get())) throw InputError(fmt::format("{}: read error", path));
  return bytes;
}

std::string read_stream_text(std::istream& in, const std::string& name) {
  std::string text;
  char chunk[1 << 16];
  for (;;) {
    in.read(chunk, sizeof chunk);
    const auto got = static_cast<size_t>(in.gcount());
    if (got == 0) break;
    if (text.size() + got > limits::kMaxFileBytes) throw InputError(too_large_message(name));
    text.append(chunk, got);
  }
  if (in.bad()) throw InputError(fmt::format("{}: read error", name));
  return text;
}

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string resolve_relative(const std::string& base_file, const std::string& relative) {
  if (!relative.empty() && relative[0] == '/') return relative;
  return directory_of(base_file) + relative;
}

std::string to_lower(std::string text) {
  for (char& c : text)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return text;
}

bool ends_with_ignoring_case(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         to_lower(text.substr(text.size() - suffix.size())) == to_lower(suffix);
}

}  // namespace cdsim
