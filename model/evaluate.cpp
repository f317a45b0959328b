#include "evaluate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <functional>
#include <thread>

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

namespace {
// 2^-bits, exactly: a table, since ldexpl per pixel cost 5% of the error measurement.
long double inverse_power_of_two(int bits) {
  static const std::array<long double, 64> table = [] {
    std::array<long double, 64> t{};
    for (size_t i = 0; i < t.size(); ++i) t[i] = std::ldexp(1.0L, -static_cast<int>(i));
    return t;
  }();
  return bits >= 0 && bits < static_cast<int>(table.size()) ? table[static_cast<size_t>(bits)] : std::ldexp(1.0L, -bits);
}
}  // namespace

PixelError pixel_error(const Fragment& f, const ExactSample& exact, int out_frac) {
  const long double scale = inverse_power_of_two(out_frac);
  const long double u = static_cast<long double>(f.u) * scale;
  const long double v = static_cast<long double>(f.v) * scale;
  PixelError e;
  e.texels = static_cast<double>(std::max(std::fabs(u - exact.u), std::fabs(v - exact.v)));
  e.footprint = e.texels / static_cast<double>(std::max(1.0L, exact.footprint));
  // floor(u) is the output's integer part, f.u >> out_frac (an arithmetic
  // shift floors); the exact texel differs when exact.u lies outside
  // [floor(u), floor(u) + 1). No floorl: GCC inlines it as frndint between
  // two rounding-mode switches, which made this function half of size's time.
  const auto outside = [](int64_t texel, long double exact_coordinate) {
    const auto lo = static_cast<long double>(texel);
    return exact_coordinate < lo || exact_coordinate >= lo + 1;
  };
  e.texel_mismatch = outside(f.u >> out_frac, exact.u) || outside(f.v >> out_frac, exact.v);
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

namespace {

// The error measurement on `threads` threads. The unit runs the triangles in
// order on the calling thread (its table and schedule carry state); their
// fragments gather until about kChunkFragments, then each fragment's exact
// sample and error are computed in parallel (most of the time: the exact
// reference in long double), and added to the statistics in the fragments'
// order by the calling thread, so that every sum is the one a single thread
// makes, bit for bit.
class ParallelErrors {
 public:
  static constexpr size_t kChunkFragments = size_t{1} << 18;
  using Sink = std::function<void(int64_t triangle, const Fragment&, const ExactSample&, const PixelError&)>;

  ParallelErrors(const PreparedScene& prepared, int subpixel_bits, int out_frac, unsigned threads)
      : prepared_(prepared), subpixel_bits_(subpixel_bits), out_frac_(out_frac), threads_(threads) {}

  void add(int64_t triangle, const std::vector<Fragment>& fragments, const Sink& sink) {
    pending_.push_back({triangle, fragments_.size(), fragments_.size() + fragments.size()});
    fragments_.insert(fragments_.end(), fragments.begin(), fragments.end());
    if (fragments_.size() >= kChunkFragments) flush(sink);
  }

  void flush(const Sink& sink) {
    samples_.resize(fragments_.size());
    errors_.resize(fragments_.size());
    // Contiguous runs of triangles of about equal fragments, one a thread;
    // the calling thread takes the last.
    std::vector<size_t> bounds(threads_ + 1, pending_.size());
    bounds[0] = 0;
    for (unsigned t = 1; t < threads_; ++t) {
      const size_t goal = fragments_.size() * t / threads_;
      bounds[t] = static_cast<size_t>(
          std::partition_point(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.begin < goal; }) -
          pending_.begin());
    }
    std::vector<std::exception_ptr> failures(threads_);
    std::vector<std::thread> workers;
    for (unsigned t = 0; t + 1 < threads_; ++t)
      workers.emplace_back([this, &bounds, &failures, t] {
        try {
          measure(bounds[t], bounds[t + 1]);
        } catch (...) {
          failures[t] = std::current_exception();
        }
      });
    try {
      measure(bounds[threads_ - 1], bounds[threads_]);
    } catch (...) {
      failures[threads_ - 1] = std::current_exception();
    }
    for (std::thread& w : workers) w.join();
    for (const std::exception_ptr& failure : failures)
      if (failure) std::rethrow_exception(failure);
    for (const Pending& p : pending_)
      for (size_t k = p.begin; k < p.end; ++k) sink(p.triangle, fragments_[k], samples_[k], errors_[k]);
    pending_.clear();
    fragments_.clear();
  }

 private:
  struct Pending {
    int64_t triangle;
    size_t begin, end;  // in fragments_
  };
  void measure(size_t first, size_t last) {
    for (size_t i = first; i < last; ++i) {
      const Pending& p = pending_[i];
      const size_t t = static_cast<size_t>(p.triangle);
      const ExactReference exact(prepared_.scene.triangles[t], prepared_.unit[t], subpixel_bits_);
      for (size_t k = p.begin; k < p.end; ++k) {
        samples_[k] = exact.at_pixel(fragments_[k].x, fragments_[k].y);
        errors_[k] = pixel_error(fragments_[k], samples_[k], out_frac_);
      }
    }
  }

  const PreparedScene& prepared_;
  int subpixel_bits_, out_frac_;
  unsigned threads_;
  std::vector<Pending> pending_;
  std::vector<Fragment> fragments_;
  std::vector<ExactSample> samples_;
  std::vector<PixelError> errors_;
};

}  // namespace

DesignResult evaluate(const PreparedScene& prepared, const Design& design, const Widths& widths,
                      bool measure_error, const FragmentVisitor* visit, unsigned threads) {
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
  // One fragment's error, in the scene's order whatever the threads.
  const auto tally = [&](int64_t triangle, const Fragment& f, const ExactSample& at, const PixelError& e) {
    if (visit) (*visit)(triangle, f, at);
    if (e.texels > result.worst.error) result.worst = {triangle, f, double(at.u), double(at.v), e.texels};
    all.add(e);
    if ((f.flags & flag::kDatapath) == 0) unflagged.add(e);
  };
  const ParallelErrors::Sink sink = tally;
  ParallelErrors parallel(prepared, widths.subpixel_bits, widths.out_frac, std::max(1u, threads));
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
    if (threads > 1) {
      parallel.add(static_cast<int64_t>(i), fragments, sink);
      continue;
    }
    const ExactReference exact(scene.triangles[i], prepared.unit[i], widths.subpixel_bits);
    for (const Fragment& f : fragments) {
      const ExactSample at = exact.at_pixel(f.x, f.y);
      tally(static_cast<int64_t>(i), f, at, pixel_error(f, at, widths.out_frac));
    }
  }
  if (threads > 1) parallel.flush(sink);
  result.table_high_water = unit.table().high_water();
  result.error = all.stats();
  result.error_unflagged = unflagged.stats();
  return result;
}

}  // namespace cdsim
