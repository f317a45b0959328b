#include "common.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "cache_files.hpp"
#include "loaders/json_structure.hpp"

namespace cdsim {

void add_common(CLI::App* app, CommonOptions& options) {
  add_scene_options(app, options.scene, options.scene_options);
  app->add_option("--design", options.designs,
                  "comma-separated designs, or all (the default; see 'cdsim designs')");
  app->add_option("--set", options.settings,
                  "NAME=VALUE: change a width or microarchitecture parameter (see 'cdsim widths'); "
                  "repeatable, each parameter once");
}

Widths widths_from(const CommonOptions& options) {
  Widths widths;
  apply_settings(widths, options.settings);
  validate(widths);
  return widths;
}

void check_output_folder(const std::string& option, const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  const std::string name = folder.empty() ? "." : folder.string();
  std::error_code ignored;
  if (!std::filesystem::is_directory(name, ignored))
    throw std::invalid_argument(fmt::format("{} {}: the folder {} does not exist", option, path, name));
  if (::access(name.c_str(), W_OK) != 0)
    throw std::invalid_argument(
        fmt::format("{} {}: cannot write into {}: {}", option, path, name, std::strerror(errno)));
}

std::vector<Design> designs_from(const std::string& list) {
  if (list == "all") return all_designs();
  const std::vector<Design> designs = parse_design_list(list);
  for (size_t i = 0; i < designs.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (designs[i].name == designs[j].name)
        throw std::invalid_argument(
            fmt::format("--design {}: design '{}' is listed twice", list, designs[i].name));
  return designs;
}

PreparedScene prepared_scene(const CommonOptions& options, const Widths& widths) {
  return prepare(load_scene(options.scene, options.scene_options), widths);
}

nlohmann::json read_json_file(const std::filesystem::path& path) {
  const std::string text = read_text_file(path);
  check_json_depth(text, path.string());
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw std::runtime_error(fmt::format("{}: not JSON: {}", path.string(), e.what()));
  }
}

}  // namespace cdsim
