// Reading whole files with a size cap and messages that name the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cdsim {

// The whole file; throws InputError when it cannot be opened or read, or when
// it is larger than limits::kMaxFileBytes.
std::vector<uint8_t> read_file_bytes(const std::string& path);

// The directory part of a path ("" for a bare file name), with a trailing '/'.
std::string directory_of(const std::string& path);

// `relative` taken relative to the directory of `base_file`, unless it is absolute.
std::string resolve_relative(const std::string& base_file, const std::string& relative);

// ASCII lower case, for extension and archive-name comparisons.
std::string to_lower(std::string text);
bool ends_with_ignoring_case(const std::string& text, const std::string& suffix);

}  // namespace cdsim
