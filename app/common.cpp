#include "common.hpp"

namespace cdsim {

void add_common(CLI::App* app, CommonOptions& options) {
  add_scene_options(app, options.scene, options.scene_options);
  app->add_option("--design", options.designs,
                  "comma-separated designs (default: all; see 'cdsim designs')");
  app->add_option("--set", options.settings,
                  "NAME=VALUE: change a width or microarchitecture parameter (see 'cdsim widths'); "
                  "repeatable");
}

Widths widths_from(const CommonOptions& options) {
  Widths widths;
  for (const auto& s : options.settings) apply_setting(widths, s);
  validate(widths);
  return widths;
}

PreparedScene prepared_scene(const CommonOptions& options, const Widths& widths) {
  return prepare(load_scene(options.scene, options.scene_options), widths);
}

}  // namespace cdsim
