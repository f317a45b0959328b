// The component area model: the unit's area without a full synthesis.
//
// Yosys elaborates the same RTL at the same widths but stops before technology
// mapping (proc, opt, wreduce: about 5 s instead of 40 to 150). Each module's
// word-level cells give a feature vector (partial-product bits of its
// multipliers, adder bits, comparator bits, multiplexer bits, flip-flop bits
// and so on); its mapped area is a linear function of them with coefficients
// fitted per module kind (setup_engine, shift_round, ...) to full syntheses of
// random configurations. The unit's blocks then add up as in cdsim area.
// `cdsim area-model` calibrates the coefficients and measures the model's
// error by leaving each configuration out of the fit in turn. docs/area.md
// gives the measured error.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <array>
#include <map>
#include <string>
#include <vector>

#include "area.hpp"

namespace cdsim {

inline constexpr std::array<const char*, 14> kAreaFeatures = {
    "mul_pp_bits", "add_bits",   "compare_bits", "equal_bits", "mux_bits",   "pmux_bits",
    "flop_bits",   "async_flop_bits", "shift_bits", "logic_bits", "reduce_bits", "other_bits",
    "const_add_bits", "rom_bits"};
using AreaFeatures = std::array<double, kAreaFeatures.size()>;
// A kind is fitted on its own when it has kSamplesPerFeature samples for
// each feature its samples have (not zero in all of them); otherwise its
// coefficients are those fitted to every kind's samples together, stored
// under kAnyKind.
inline constexpr const char* kAnyKind = "*";
inline constexpr size_t kSamplesPerFeature = 2;

// Per module kind, area = coefficients . features.
struct AreaModel {
  std::map<std::string, AreaFeatures> coefficients;
  std::string liberty;    // the file name it was calibrated on
  std::string rtl_hash;   // of rtl/*.sv at calibration
  nlohmann::json calibration;  // how it was made (command, seed, configurations, samples)
};

// Loads the model (default: rtl/area_model.json). Throws naming the file when
// it is missing or malformed.
AreaModel load_area_model(const std::string& path);
std::string default_area_model_path();
// A hash of the scan unit's RTL sources (those the model is calibrated on) and
// the elaboration flow (default: this build's).
std::string rtl_sources_hash(const std::string& flow = "");
// The calibration archive (default: rtl/area_calibration.json): per
// configuration key, its synthesised areas and elaborated inventory, so that a
// calibration need not synthesise again what an earlier one did. Empty when the
// file is missing. An archive of another elaboration flow keeps the synthesis
// figures of every entry whose RTL sources are unchanged and drops their
// inventories, which the calibration then elaborates again. Throws naming the
// file when malformed.
nlohmann::json load_area_archive(const std::string& path);
std::string default_area_archive_path();

// The unit's area by the model, cached like a synthesis. Throws when the model
// has no coefficients for a module kind the design holds.
AreaReport estimate_area(const Design& design, const Widths& widths, const AreaOptions& options);

// Random valid widths for calibration: every parameter uniform in its
// widths.def range, the table 4 to 4096 lines, the walker's accumulator
// within 64 bits (as when the committed archive was drawn); reproducible from
// (seed, tag, index).
Widths random_widths(uint64_t seed, const std::string& tag, int index);

// The features one word-level cell of Yosys's JSON netlist adds to its module's.
void add_cell_features(const std::string& type, const nlohmann::json& cell, AreaFeatures& features);

// One module of one calibration configuration: its kind, features and
// synthesised own area.
struct AreaSample {
  std::string kind;
  AreaFeatures features{};
  double area = 0;
  size_t config = 0;
};
// Non-negative least squares per kind over the samples not of configuration
// `leave_out` (no feature takes area away; among equal fits on the features
// kept, the smallest coefficients), and over all of them as kAnyKind.
std::map<std::string, AreaFeatures> fit_area_coefficients(const std::vector<AreaSample>& samples,
                                                          size_t leave_out);

struct AreaModelOptions {
  int configs = 20;       // random configurations per design
  uint64_t seed = 1;
  std::string designs = "all";
  unsigned jobs = 0;
  std::string write_path;  // default: rtl/area_model.json
  std::string json_path;
  std::string archive_path;  // default: rtl/area_calibration.json
  bool no_archive = false;
  bool archive_only = false;
  AreaOptions area;
};

CLI::App* add_area_model_command(CLI::App& app, AreaModelOptions& options);
int run_area_model_command(const AreaModelOptions& options);

}  // namespace cdsim
