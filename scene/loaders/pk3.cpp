#include "pk3.hpp"

#include <fmt/format.h>
#include <zip.h>

#include <cstring>

#include "file_io.hpp"
#include "limits.hpp"
#include "triangle.hpp"

namespace cdsim {

struct Pk3Archive::Handle {
  zip_t* archive = nullptr;
  std::vector<uint8_t> bytes;  // backing store of an in-memory archive
  ~Handle() {
    if (archive) zip_discard(archive);
  }
};

Pk3Archive::Pk3Archive(std::unique_ptr<Handle> handle, std::string name)
    : handle_(std::move(handle)), name_(std::move(name)) {}
Pk3Archive::Pk3Archive(Pk3Archive&&) noexcept = default;
Pk3Archive& Pk3Archive::operator=(Pk3Archive&&) noexcept = default;
Pk3Archive::~Pk3Archive() = default;

namespace {

std::string zip_message(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string text = zip_error_strerror(&error);
  zip_error_fini(&error);
  return text;
}

}  // namespace

Pk3Archive Pk3Archive::open_file(const std::string& path) {
  require_regular_file(path);
  auto handle = std::make_unique<Handle>();
  int code = 0;
  handle->archive = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &code);
  if (!handle->archive)
    throw InputError(fmt::format("{}: cannot open as a zip (.pk3) archive: {}", path,
                                 zip_message(code)));
  return Pk3Archive(std::move(handle), path);
}

Pk3Archive Pk3Archive::open_memory(std::vector<uint8_t> bytes, const std::string& name) {
  auto handle = std::make_unique<Handle>();
  handle->bytes = std::move(bytes);
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source =
      zip_source_buffer_create(handle->bytes.data(), handle->bytes.size(), 0, &error);
  if (source) handle->archive = zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &error);
  if (!handle->archive) {
    const std::string text = zip_error_strerror(&error);
    zip_error_fini(&error);
    if (source) zip_source_free(source);
    throw InputError(fmt::format("{}: cannot open as a zip (.pk3) archive: {}", name, text));
  }
  zip_error_fini(&error);
  return Pk3Archive(std::move(handle), name);
}

std::vector<std::string> Pk3Archive::entries() const {
  std::vector<std::string> names;
  const zip_int64_t count = zip_get_num_entries(handle_->archive, 0);
  for (zip_int64_t i = 0; i < count; ++i) {
    const char* entry = zip_get_name(handle_->archive, static_cast<zip_uint64_t>(i), 0);
    if (entry) names.emplace_back(entry);
  }
  return names;
}

bool Pk3Archive::contains(const std::string& entry) const {
  return zip_name_locate(handle_->archive, entry.c_str(), ZIP_FL_NOCASE) >= 0;
}

std::optional<std::vector<uint8_t>> Pk3Archive::read(const std::string& entry) const {
  const zip_int64_t index = zip_name_locate(handle_->archive, entry.c_str(), ZIP_FL_NOCASE);
  if (index < 0) return std::nullopt;
  const auto where = [&] { return fmt::format("{}:{}", name_, entry); };
  // Zip marks a directory by a trailing '/' in its entry name.
  const char* stored = zip_get_name(handle_->archive, static_cast<zip_uint64_t>(index), 0);
  if (stored && *stored && stored[std::strlen(stored) - 1] == '/')
    throw InputError(fmt::format("{}: is a directory in the archive, not a file", where()));
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_stat_index(handle_->archive, static_cast<zip_uint64_t>(index), 0, &stat) != 0 ||
      !(stat.valid & ZIP_STAT_SIZE))
    throw InputError(fmt::format("{}: cannot read the entry's size: {}", where(),
                                 zip_strerror(handle_->archive)));
  if (stat.size > limits::kMaxFileBytes)
    throw InputError(fmt::format("{}: entry of {} bytes is larger than the {} MiB cap", where(),
                                 stat.size, limits::kMaxFileBytes >> 20));
  zip_file_t* file = zip_fopen_index(handle_->archive, static_cast<zip_uint64_t>(index), 0);
  if (!file)
    throw InputError(fmt::format("{}: cannot open the entry: {}", where(),
                                 zip_strerror(handle_->archive)));
  std::vector<uint8_t> bytes(static_cast<size_t>(stat.size));
  size_t done = 0;
  std::string failure;
  while (done < bytes.size()) {
    const zip_int64_t got = zip_fread(file, bytes.data() + done, bytes.size() - done);
    if (got < 0) {
      failure = zip_file_strerror(file);
      break;
    }
    if (got == 0) {
      failure = fmt::format("ends after {} of {} bytes", done, bytes.size());
      break;
    }
    done += static_cast<size_t>(got);
  }
  if (failure.empty()) {
    // One more read reaches the end of the stream, where libzip checks the CRC.
    uint8_t extra = 0;
    const zip_int64_t got = zip_fread(file, &extra, 1);
    if (got < 0) failure = zip_file_strerror(file);
    if (got > 0) failure = fmt::format("longer than the {} bytes its header gives", bytes.size());
  }
  const int closed = zip_fclose(file);
  if (failure.empty() && closed != 0) failure = zip_message(closed);
  if (!failure.empty()) throw InputError(fmt::format("{}: corrupt entry: {}", where(), failure));
  return bytes;
}

std::optional<std::pair<std::string, std::string>> split_pk3_spec(const std::string& spec) {
  const std::string lower = to_lower(spec);
  const auto at = lower.find(".pk3:");
  if (at == std::string::npos) return std::nullopt;
  return std::make_pair(spec.substr(0, at + 4), spec.substr(at + 5));
}

}  // namespace cdsim
