// Quake 3 .pk3 archives (plain zip files), read with libzip.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cdsim {

class Pk3Archive {
 public:
  // Opens an archive on disk or a copy of one in memory (`name` for messages).
  // Throws InputError when it is not a regular file or not a readable zip archive.
  static Pk3Archive open_file(const std::string& path);
  static Pk3Archive open_memory(std::vector<uint8_t> bytes, const std::string& name);

  Pk3Archive(Pk3Archive&&) noexcept;
  Pk3Archive& operator=(Pk3Archive&&) noexcept;
  ~Pk3Archive();

  const std::string& name() const { return name_; }

  // Entry names, in archive order.
  std::vector<std::string> entries() const;

  // Whether the archive holds `entry` (ignoring case).
  bool contains(const std::string& entry) const;

  // The entry's bytes, looked up ignoring case as Quake does; nothing when
  // absent. Throws InputError for a directory entry, a corrupt entry or one
  // over the size cap (limits::kMaxFileBytes).
  std::optional<std::vector<uint8_t>> read(const std::string& entry) const;

 private:
  struct Handle;
  Pk3Archive(std::unique_ptr<Handle> handle, std::string name);
  std::unique_ptr<Handle> handle_;
  std::string name_;
};

// "FILE.pk3:maps/NAME.bsp" split into ("FILE.pk3", "maps/NAME.bsp"); nothing
// when `spec` names no archive member.
std::optional<std::pair<std::string, std::string>> split_pk3_spec(const std::string& spec);

}  // namespace cdsim
