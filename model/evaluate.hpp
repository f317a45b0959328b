// Runs a scene through one design and measures speed, cost and error (SPEC §5, §8).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "design.hpp"
#include "scan_unit.hpp"
#include "screen_scene.hpp"

namespace cdsim {

struct PreparedScene {
  Scene scene;
  std::vector<UnitTriangle> unit;  // snapped and quantised, one per scene triangle
};

// Validates and snaps every triangle; throws InputError naming the first bad one.
PreparedScene prepare(const Scene& scene, const Widths& widths);

struct ErrorStats {
  double mean = 0, rms = 0, p99 = 0, max = 0;  // texels, per pixel max(|du|, |dv|)
  double footprint_max = 0;    // max of error / max(1, rho)
  double texel_mismatch = 0;   // share of pixels whose nearest texel differs from exact
  double over_lsb = 0;         // share of pixels with error > 2^-out_frac
};

// The pixel with the largest error, to make a bad figure easy to chase.
struct WorstPixel {
  int64_t triangle = -1;
  Fragment fragment;
  double exact_u = 0, exact_v = 0, error = 0;
};

struct DesignResult {
  Design design;
  int64_t triangles = 0, pixels = 0;
  // The scene's clocks, from the first triangle accepted to the last record
  // delivered, both included (no back-pressure): the sum of the triangles'
  // clocks (timing.hpp), which add up as setup-bound + fill-bound + walk + record.
  int64_t cycles = 0, setup_cycles = 0, fill_cycles = 0, walk_cycles = 0, record_cycles = 0;
  int64_t lines = 0, banded_triangles = 0, x_major_triangles = 0, y_major_triangles = 0;
  // Designs with a divide fallback: the triangles and pixels it walked.
  int64_t fallback_triangles = 0, fallback_pixels = 0;
  int table_depth = 0, table_word_bits = 0;
  int64_t table_bits = 0, table_high_water = 0;
  ErrorStats error;             // over every pixel
  // Pixels that carry a datapath flag (flag::kDatapath: a table entry or an
  // output left its format, a 1/w left its range, a correction was dropped),
  // and the error over the others, so that a few wild pixels cannot hide in
  // the statistics of all of them (docs/scenes.md, "Flags").
  int64_t flagged_pixels = 0;
  ErrorStats error_unflagged;
  std::array<int64_t, flag::kCount> flagged_triangles{};  // triangles raising each flag
  WorstPixel worst;
  double pixels_per_clock() const { return cycles ? double(pixels) / double(cycles) : 0.0; }
};

// Per-pixel error of one fragment against the exact reference.
struct ExactSample;
struct PixelError;

// Gathers per-pixel errors into ErrorStats.
class ErrorAccumulator {
 public:
  explicit ErrorAccumulator(int out_frac) : lsb_(std::ldexp(1.0, -out_frac)) {}
  void add(const PixelError& e);
  ErrorStats stats();  // sorts a copy's worth in place: call once, at the end

 private:
  double lsb_;
  std::vector<float> errors_;
  double sum_ = 0, sum_squares_ = 0;
  int64_t mismatches_ = 0, over_lsb_ = 0;
  double max_ = 0, footprint_max_ = 0;
};

struct PixelError {
  double texels = 0, footprint = 0;
  bool texel_mismatch = false;
};
PixelError pixel_error(const Fragment& fragment, const struct ExactSample& exact, int out_frac);

// Called for every fragment whose error is measured, with its triangle's index.
using FragmentVisitor = std::function<void(int64_t triangle, const Fragment&, const ExactSample&)>;

// With threads > 1 the error measurement (the exact reference of every
// fragment) runs on that many threads; the result is the same bit for bit.
DesignResult evaluate(const PreparedScene& scene, const Design& design, const Widths& widths,
                      bool measure_error = true, const FragmentVisitor* visit = nullptr,
                      unsigned threads = 1);

}  // namespace cdsim
