// Options every cdsim subcommand shares: scene, designs, width settings.
#pragma once

#include <CLI/CLI.hpp>
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
Widths widths_from(const CommonOptions& options);
PreparedScene prepared_scene(const CommonOptions& options, const Widths& widths);

}  // namespace cdsim
