// Options every cdsim subcommand shares: scene, designs, width settings.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "evaluate.hpp"
#include "loaders/scene_cli.hpp"
#include "scene.hpp"
#include "widths.hpp"

namespace cdsim {

struct CommonOptions {
  std::string scene = "default";
  SceneOptions scene_options;
  std::string designs;
  std::vector<std::string> settings;
};

void add_common(CLI::App* app, CommonOptions& options);
// The widths of the --set options (each parameter at most once), validated.
Widths widths_from(const CommonOptions& options);
// Refuses, before a long run, an output file whose folder is missing or not
// writable (the write itself is checked again).
void check_output_folder(const std::string& option, const std::string& path);
// parse_design_list, refusing a design named twice; "all" is every design.
std::vector<Design> designs_from(const std::string& list);
PreparedScene prepared_scene(const CommonOptions& options, const Widths& widths);
// A JSON file that cdsim wrote (a shard's summary, a cache entry, the area
// model and its archive), its nesting depth checked before the parse
// (scene/loaders/json_structure.hpp): throws naming the file.
nlohmann::json read_json_file(const std::filesystem::path& path);

}  // namespace cdsim
