#include "evaluate.hpp"

#include <algorithm>
#include <cmath>

#include "exact.hpp"
#include "interrupt.hpp"

namespace cdsim {

PreparedScene prepare(const Scene& scene, const Widths& widths) {
  validate(widths);
  PreparedScene out;
  out.scene = scene;
  out.unit.reserve(scene.triangles.size());
  for (size_t i = 0; i < scene.triangles.size(); ++i)
    out.unit.push_back(to_unit(scene.triangles[i], widths, i));
  return out;
}

PixelError pixel_error(const Fragment& f, const ExactSample& exact, int out_frac) {
  const long double scale = std::ldexp(1.0L, -out_frac);
  const long double u = static_cast<long double>(f.u) * scale;
  const long double v = static_cast<long double>(f.v) * scale;
  PixelError e;
  e.texels = static_cast<double>(std::max(std::fabs(u - exact.u), std::fabs(v - exact.v)));
  e.footprint = e.texels / static_cast<double>(std::max(1.0L, exact.footprint));
  e.texel_mismatch = std::floor(u) != std::floor(exact.u) || std::floor(v) != std::floor(exact.v);
  return e;
}

DesignResult evaluate(const PreparedScene& prepared, const Design& design, const Widths& widths,
                      bool measure_error, const FragmentVisitor* visit) {
  const Scene& scene = prepared.scene;
  ScanUnit unit(design, widths, scene.width, scene.height);
  DesignResult result;
  result.design = design;
  result.triangles = static_cast<int64_t>(prepared.unit.size());
  if (design.kind == Design::Kind::ConstantDepth) {
    result.table_depth = widths.table_depth * design.density;
    result.table_word_bits = widths.table_word_bits(design.persp);
    result.table_bits = int64_t{result.table_depth} * widths.table_banks * result.table_word_bits;
  }
  std::vector<float> errors;
  double sum = 0, sum_squares = 0;
  int64_t mismatches = 0, over_lsb = 0;
  const double lsb = std::ldexp(1.0, -widths.out_frac);
  // Kept across calls: a fresh buffer per pass costs page faults that would
  // dominate the model's own time.
  static thread_local std::vector<Fragment> fragments;
  for (size_t i = 0; i < prepared.unit.size(); ++i) {
    throw_if_interrupted();  // SIGINT: every command that evaluates stops within a triangle
    fragments.clear();
    const TriangleRecord r = unit.run(prepared.unit[i], &fragments);
    result.pixels += r.pixels;
    result.cycles += r.cycles;
    result.setup_cycles += r.setup_cycles;
    result.fill_cycles += r.fill_cycles;
    result.walk_cycles += r.walk_cycles;
    result.record_cycles += r.record_cycles;
    result.lines += r.lines;
    result.banded_triangles += r.bands > 1;
    (r.x_major ? result.x_major_triangles : result.y_major_triangles) += 1;
    for (int bit = 0; bit < flag::kCount; ++bit) result.flagged_triangles[size_t(bit)] += (r.flags >> bit) & 1;
    if (!measure_error || fragments.empty()) continue;
    const ExactReference exact(scene.triangles[i], prepared.unit[i], widths.subpixel_bits);
    for (const Fragment& f : fragments) {
      const ExactSample at = exact.at_pixel(f.x, f.y);
      if (visit) (*visit)(static_cast<int64_t>(i), f, at);
      const PixelError e = pixel_error(f, at, widths.out_frac);
      errors.push_back(static_cast<float>(e.texels));
      sum += e.texels;
      sum_squares += e.texels * e.texels;
      if (e.texels > result.worst.error) {
        result.worst = {static_cast<int64_t>(i), f, double(at.u), double(at.v), e.texels};
      }
      result.error.max = std::max(result.error.max, e.texels);
      result.error.footprint_max = std::max(result.error.footprint_max, e.footprint);
      mismatches += e.texel_mismatch;
      over_lsb += e.texels > lsb;
    }
  }
  result.table_high_water = unit.table().high_water();
  if (!errors.empty()) {
    const double n = double(errors.size());
    result.error.mean = sum / n;
    result.error.rms = std::sqrt(sum_squares / n);
    const size_t rank = std::min(errors.size() - 1, static_cast<size_t>(std::ceil(0.99 * n)) - 1);
    std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(rank), errors.end());
    result.error.p99 = errors[rank];
    result.error.texel_mismatch = double(mismatches) / n;
    result.error.over_lsb = double(over_lsb) / n;
  }
  return result;
}

}  // namespace cdsim
