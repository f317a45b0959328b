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
// The widths of the --set options (each parameter at most once), validated.
Widths widths_from(const CommonOptions& options);
// Refuses, before a long run, an output file whose folder is missing or not
// writable (the write itself is checked again).
void check_output_folder(const std::string& option, const std::string& path);
// parse_design_list, refusing a design named twice.
std::vector<Design> designs_from(const std::string& list);
PreparedScene prepared_scene(const CommonOptions& options, const Widths& widths);

// --shard I/N: the I-th of N shards (1-based) takes every N-th item from the
// (I-1)-th, so that each item is in exactly one shard and items keep their
// seeds and order. A default Shard is the whole run.
struct Shard {
  uint64_t index = 1, count = 1;
  bool whole() const { return count == 1; }
  bool holds(uint64_t item) const { return item % count == index - 1; }
};
// Parses "I/N" (1 <= I <= N <= 10^6); throws std::invalid_argument naming the option.
Shard parse_shard(const std::string& option, const std::string& text);

}  // namespace cdsim
