// cdsim render: PNG pictures of a scene per design, a checkerboard sampled at
// each design's (u, v) beside the exact result, and an error heat map (the
// paper's Fig. 7).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "common.hpp"

namespace cdsim {

struct RenderOptions {
  CommonOptions common;
  std::string out = "render-out";
  int checker_texels = 64;  // side of one checker square, texels
};

CLI::App* add_render_command(CLI::App& app, RenderOptions& options);
int run_render_command(const RenderOptions& options);

}  // namespace cdsim
