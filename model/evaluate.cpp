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

void ErrorAccumulator::add(const PixelError& e) {
  errors_.push_back(static_cast<float>(e.texels));
  sum_ += e.texels;
  sum_squares_ += e.texels * e.texels;
  max_ = std::max(max_, e.texels);
  footprint_max_ = std::max(footprint_max_, e.footprint);
  mismatches_ += e.texel_mismatch;
  over_lsb_ += e.texels > lsb_;
}

ErrorStats ErrorAccumulator::stats() {
  ErrorStats s;
  s.max = max_;
  s.footprint_max = footprint_max_;
  if (errors_.empty()) return s;
  const double n = double(errors_.size());
  s.mean = sum_ / n;
  s.rms = std::sqrt(sum_squares_ / n);
  const size_t rank = std::min(errors_.size() - 1, static_cast<size_t>(std::ceil(0.99 * n)) - 1);
  std::nth_element(errors_.begin(), errors_.begin() + static_cast<std::ptrdiff_t>(rank), errors_.end());
  s.p99 = errors_[rank];
  s.texel_mismatch = double(mismatches_) / n;
  s.over_lsb = double(over_lsb_) / n;
  return s;
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
  ErrorAccumulator all(widths.out_frac), unflagged(widths.out_frac);
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
    result.fallback_triangles += r.fallback;
    result.fallback_pixels += r.fallback ? r.pixels : 0;
    (r.x_major ? result.x_major_triangles : result.y_major_triangles) += 1;
    for (int bit = 0; bit < flag::kCount; ++bit) result.flagged_triangles[size_t(bit)] += (r.flags >> bit) & 1;
    for (const Fragment& f : fragments) result.flagged_pixels += (f.flags & flag::kDatapath) != 0;
    if (!measure_error || fragments.empty()) continue;
    const ExactReference exact(scene.triangles[i], prepared.unit[i], widths.subpixel_bits);
    for (const Fragment& f : fragments) {
      const ExactSample at = exact.at_pixel(f.x, f.y);
      if (visit) (*visit)(static_cast<int64_t>(i), f, at);
      const PixelError e = pixel_error(f, at, widths.out_frac);
      if (e.texels > result.worst.error) {
        result.worst = {static_cast<int64_t>(i), f, double(at.u), double(at.v), e.texels};
      }
      all.add(e);
      if ((f.flags & flag::kDatapath) == 0) unflagged.add(e);
    }
  }
  result.table_high_water = unit.table().high_water();
  result.error = all.stats();
  result.error_unflagged = unflagged.stats();
  return result;
}

}  // namespace cdsim
