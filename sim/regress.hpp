// `cdsim regress`: the RTL (Verilated, under SystemC) against the C++ model.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "scene.hpp"
#include "widths.hpp"

namespace CLI {
class App;
}

namespace cdsim::rtl {

// Registers the `regress` subcommand and its options on app.
CLI::App* add_regress_command(CLI::App& app);
// Runs it with the parsed options; returns the process exit code.
int run_regress_command();

// `cdsim size --verify`: regresses exactly these widths on the RTL, verilated
// into the cache on first use as for `cdsim regress --set`: the scene, then
// `random` seeded random triangles, with back-pressure. Prints what regress
// prints; returns its exit code (0: no mismatch).
struct VerifyRequest {
  Widths widths;
  std::string scene = "default";
  SceneOptions scene_options;
  std::string design;  // a constant-depth design (the RTL has no other)
  size_t random = 2000;
  uint64_t seed = 1;
  double backpressure = 0.3;
  std::string rtl_cache;  // empty: the default cache folder
};
int verify_widths(const VerifyRequest& request);

}  // namespace cdsim::rtl
