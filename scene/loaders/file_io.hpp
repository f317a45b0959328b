// Reading whole files with a size cap and messages that name the file.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace cdsim {

// Throws InputError unless `path` names a regular file (after symbolic links):
// a missing file, a directory, a device (/dev/zero, /dev/null), a FIFO or a
// socket is refused by name before anything opens it.
void require_regular_file(const std::string& path);

// The whole file; throws InputError when it is not a regular file, cannot be
// opened or read, or is larger than limits::kMaxFileBytes.
std::vector<uint8_t> read_file_bytes(const std::string& path);

// The rest of `in`, up to limits::kMaxFileBytes; `name` names it in messages.
std::string read_stream_text(std::istream& in, const std::string& name);

// The InputError message for an input over limits::kMaxFileBytes.
std::string too_large_message(const std::string& name);

// The directory part of a path ("" for a bare file name), with a trailing '/'.
std::string directory_of(const std::string& path);

// `relative` taken relative to the directory of `base_file`, unless it is absolute.
std::string resolve_relative(const std::string& base_file, const std::string& relative);

// ASCII lower case, for extension and archive-name comparisons.
std::string to_lower(std::string text);
bool ends_with_ignoring_case(const std::string& text, const std::string& suffix);

}  // namespace cdsim
