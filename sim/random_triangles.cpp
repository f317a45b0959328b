#include "random_triangles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

namespace cdsim::rtl {

namespace {

uint32_t float_bits(float f) {
  uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  return bits;
}

// 1/w as binary32 from an exponent (biased) and a 24-bit mantissa with its hidden bit.
uint32_t q_bits_of(int exponent, int64_t mantissa) {
  mantissa = std::clamp<int64_t>(mantissa, int64_t{1} << 23, (int64_t{1} << 24) - 1);
  return (static_cast<uint32_t>(exponent) << 23) | static_cast<uint32_t>(mantissa & 0x7fffff);
}

class Generator {
 public:
  Generator(uint64_t seed, const Widths& w) : rng_(seed), w_(w) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  int64_t integer(int64_t lo, int64_t hi) { return std::uniform_int_distribution<int64_t>(lo, hi)(rng_); }
  bool chance(double p) { return uniform(0, 1) < p; }

  int64_t pos(double pixels) { return static_cast<int64_t>(std::nearbyint(std::ldexp(pixels, w_.subpixel_bits))); }
  int64_t tex(double texels) { return static_cast<int64_t>(std::nearbyint(std::ldexp(texels, w_.uv_in_frac))); }
  // Largest legal texture coordinate magnitude: just under 2^15 texels.
  int64_t tex_limit() { return (int64_t{1} << (15 + w_.uv_in_frac)) - 1; }
  uint32_t q_of_w(double w) { return float_bits(static_cast<float>(1.0 / w)); }

  void random_uv(UnitVertex& v, double range) {
    v.u = tex(uniform(-range, range));
    v.v = tex(uniform(-range, range));
  }

  Job make(size_t index) {
    Job job;
    job.viewport_width = 64;
    job.viewport_height = 48;
    auto& t = job.triangle;
    const int kind = static_cast<int>(integer(0, 99));
    const char* name = "generic";
    if (kind < 40) {
      name = "generic";
      for (auto& v : t.vertex) {
        v.x = pos(uniform(-10, 74));
        v.y = pos(uniform(-10, 58));
        v.q_float = q_of_w(std::exp(uniform(std::log(0.05), std::log(50.0))));
        random_uv(v, 300);
      }
    } else if (kind < 46) {
      name = "parallel to screen";
      const uint32_t q = q_of_w(uniform(0.1, 20));
      for (auto& v : t.vertex) {
        v.x = pos(uniform(-4, 68));
        v.y = pos(uniform(-4, 52));
        v.q_float = q;
        random_uv(v, 500);
      }
    } else if (kind < 58) {
      // q changes equally in x and y: |g| = 1 exactly, one LSB either side, or
      // |g| = 1/2 so that g o lands on .5.
      name = "|g| = 1 +- 1 LSB / g = 1/2";
      const int64_t x0 = integer(0, 20), y0 = integer(0, 10), side = integer(4, 40);
      const int64_t one = int64_t{1} << w_.subpixel_bits;
      t.vertex[0].x = x0 * one + integer(0, one - 1);
      t.vertex[0].y = y0 * one + integer(0, one - 1);
      t.vertex[1].x = t.vertex[0].x + side * one;
      t.vertex[1].y = t.vertex[0].y;
      t.vertex[2].x = t.vertex[0].x;
      t.vertex[2].y = t.vertex[0].y + side * one;
      if (chance(0.5)) std::swap(t.vertex[1], t.vertex[2]);  // other winding
      const int exponent = static_cast<int>(integer(120, 128));
      const int64_t m0 = integer(int64_t{3} << 21, int64_t{5} << 21);
      const int64_t d = integer(int64_t{1} << 12, int64_t{1} << 21) * (chance(0.5) ? 1 : -1);
      const int64_t lsb = std::max<int64_t>(1, std::llabs(d) >> w_.g_frac);
      int64_t d2 = chance(0.5) ? d : -d;
      if (chance(0.25)) d2 = 2 * d2;  // |g| = 1/2 the other way round
      d2 += integer(-1, 1) * lsb;
      t.vertex[0].q_float = q_bits_of(exponent, m0);
      t.vertex[1].q_float = q_bits_of(exponent, m0 + d);
      t.vertex[2].q_float = q_bits_of(exponent, m0 + d2);
      for (auto& v : t.vertex) random_uv(v, 200);
    } else if (kind < 66) {
      name = "sliver";
      job.viewport_width = 512;
      job.viewport_height = 512;
      const double x0 = uniform(-20, 200), y0 = uniform(-20, 200);
      const double len = uniform(20, 300), angle = uniform(0, 2 * M_PI);
      const double width = uniform(0.05, 0.9);
      t.vertex[0].x = pos(x0);
      t.vertex[0].y = pos(y0);
      t.vertex[1].x = pos(x0 + len * std::cos(angle));
      t.vertex[1].y = pos(y0 + len * std::sin(angle));
      t.vertex[2].x = pos(x0 + len * std::cos(angle) - width * std::sin(angle));
      t.vertex[2].y = pos(y0 + len * std::sin(angle) + width * std::cos(angle));
      for (auto& v : t.vertex) {
        v.q_float = q_of_w(std::exp(uniform(std::log(0.1), std::log(100.0))));
        random_uv(v, 2000);
      }
    } else if (kind < 72) {
      name = "sub-pixel";
      const double x0 = uniform(0, 60), y0 = uniform(0, 44);
      for (auto& v : t.vertex) {
        v.x = pos(x0 + uniform(0, 1.2));
        v.y = pos(y0 + uniform(0, 1.2));
        v.q_float = q_of_w(uniform(0.5, 5));
        random_uv(v, 100);
      }
    } else if (kind < 76) {
      name = "zero area";
      const double x0 = uniform(0, 60), y0 = uniform(0, 44), dx = uniform(-30, 30), dy = uniform(-30, 30);
      for (int i = 0; i < 3; ++i) {
        const double s = chance(0.3) ? 0.0 : uniform(0, 1);
        t.vertex[i].x = pos(x0) + static_cast<int64_t>(std::nearbyint(s * double(pos(dx))));
        t.vertex[i].y = pos(y0) + static_cast<int64_t>(std::nearbyint(s * double(pos(dy))));
        if (i == 2) {  // exactly on the line through the first two (integer multiple)
          t.vertex[2].x = t.vertex[0].x + 2 * (t.vertex[1].x - t.vertex[0].x);
          t.vertex[2].y = t.vertex[0].y + 2 * (t.vertex[1].y - t.vertex[0].y);
        }
        t.vertex[i].q_float = q_of_w(uniform(0.5, 5));
        random_uv(t.vertex[i], 100);
      }
    } else if (kind < 84) {
      name = "edge-on, depth ratio 1e4";
      for (auto& v : t.vertex) {
        v.x = pos(uniform(-10, 74));
        v.y = pos(uniform(-10, 58));
        random_uv(v, 1000);
      }
      const double near = uniform(0.01, 0.05);
      t.vertex[0].q_float = q_of_w(near);
      t.vertex[1].q_float = q_of_w(near * 1e4);
      t.vertex[2].q_float = q_of_w(near * std::exp(uniform(0, std::log(1e4))));
    } else if (kind < 90) {
      name = "texture coordinates near +-2^15";
      for (auto& v : t.vertex) {
        v.x = pos(uniform(-4, 68));
        v.y = pos(uniform(-4, 52));
        v.q_float = q_of_w(uniform(0.2, 20));
        v.u = (chance(0.5) ? 1 : -1) * (tex_limit() - integer(0, int64_t{1} << (w_.uv_in_frac + 6)));
        v.v = (chance(0.5) ? 1 : -1) * (tex_limit() - integer(0, int64_t{1} << (w_.uv_in_frac + 6)));
      }
    } else if (kind < 95) {
      name = "vertices on pixel centres";
      const int64_t one = int64_t{1} << w_.subpixel_bits, half = one / 2;
      for (auto& v : t.vertex) {
        v.x = integer(-2, 66) * one + half;
        v.y = integer(-2, 50) * one + half;
        v.q_float = q_of_w(uniform(0.5, 10));
        random_uv(v, 300);
      }
    } else {
      // Tall and narrow with depth changing along it: more lines than the table.
      name = "more lines than the table";
      job.viewport_width = 64;
      job.viewport_height = 4096;
      const double height = uniform(1200, 3000);
      const double x0 = uniform(2, 50), width = uniform(1, 6);
      t.vertex[0].x = pos(x0);
      t.vertex[0].y = pos(uniform(-5, 5));
      t.vertex[1].x = pos(x0 + width);
      t.vertex[1].y = pos(uniform(-5, 5));
      t.vertex[2].x = pos(x0 + uniform(0, width));
      t.vertex[2].y = pos(height);
      t.vertex[0].q_float = q_of_w(uniform(0.5, 1));
      t.vertex[1].q_float = q_of_w(uniform(0.5, 1));
      t.vertex[2].q_float = q_of_w(uniform(20, 200));
      for (auto& v : t.vertex) random_uv(v, 4000);
    }
    job.origin = fmt::format("random {} ({})", index, name);
    return job;
  }

 private:
  std::mt19937_64 rng_;
  Widths w_;
};

}  // namespace

std::vector<Job> random_jobs(size_t count, uint64_t seed, const Widths& widths,
                             const std::vector<const Design*>& designs) {
  Generator generator(seed, widths);
  std::vector<Job> jobs;
  jobs.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    Job job = generator.make(i);
    job.design = designs[i % designs.size()];
    jobs.push_back(std::move(job));
  }
  return jobs;
}

}  // namespace cdsim::rtl
