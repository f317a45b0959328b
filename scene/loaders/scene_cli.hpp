// The scene options of every cdsim subcommand, for CLI11 front ends (app/,
// sim/): --scene, --camera, --spawn, --resolution. Header-only so that the
// scene library does not depend on CLI11.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "scene.hpp"

namespace cdsim {

inline void add_scene_options(CLI::App* app, std::string& scene, SceneOptions& options) {
  app->add_option("--scene", scene,
                  "'default' (embedded corridor), 'dense' (embedded sphere of small triangles), a .tri triangle list, a .json scene file, a mesh "
                  "(.obj, .gltf, .glb) with --camera, or a Quake 3 map (.bsp or "
                  "FILE.pk3:maps/NAME.bsp) with --spawn or --camera (docs/scenes.md)")
      ->capture_default_str();
  app->add_option("--camera", options.camera,
                  "ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_y[,near]: eye, target, up vector and vertical "
                  "field of view in degrees, in the mesh's own coordinates");
  app->add_option("--spawn", options.spawn,
                  "N: the camera of a Quake 3 map's Nth spawn point (from 0)")
      ->check(CLI::Range(0, 1000000));
  app->add_option("--resolution", options.resolution, "WxH viewport, up to 8192x8192");
}

}  // namespace cdsim
