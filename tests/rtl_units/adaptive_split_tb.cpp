// rtl/adaptive_split.sv against the model's split engine
// (model/adaptive_split.cpp), at every configuration in
// adaptive_split_configs.hpp, bit and cycle exact:
//  - the leaves of each triangle, in order: vertices (x, y, 1/w as binary32,
//    u, v) and depth;
//  - the cycle each leaf is first offered: its engine cycles after the cycle
//    after the previous leaf was taken (the first: after the intake);
//  - the cycle the next triangle can be accepted: after the last leaf was
//    taken and the dropped sub-triangles after it, with tri_done_o and the
//    triangle's flags.
// The leaf sink stalls at random, so leaves wait in the output register.
// Triangles: random ones with depth ratios up to 30 (many split), some far
// off the viewport (dropped sub-triangles), flat ones (nothing splits) and
// zero-area ones (offered whole).
#include <type_traits>
#include <vector>

#include "adaptive_split.hpp"
#include "adaptive_split_configs.hpp"
#include "design.hpp"
#include "tb_support.hpp"
#include "../test_support.hpp"

namespace {

using namespace rtl_units;
using cdsim::AdaptiveLeaf;
using cdsim::AdaptiveSplit;
using cdsim::UnitTriangle;
using cdsim::Widths;

constexpr int kWidth = 96, kHeight = 72;

// Bits of a flattened port, whatever Verilator made of it (an integer, or
// VlWide words).
template <std::size_t N>
bool bit(const VlWide<N>& port, int i) {
  return (port[static_cast<std::size_t>(i / 32)] >> (i % 32)) & 1u;
}
template <std::size_t N>
void set_bit(VlWide<N>& port, int i, bool value) {
  EData& word = port[static_cast<std::size_t>(i / 32)];
  word = value ? word | (EData{1} << (i % 32)) : word & ~(EData{1} << (i % 32));
}
template <class T, class = std::enable_if_t<std::is_integral_v<T>>>
bool bit(const T& port, int i) {
  return (static_cast<uint64_t>(port) >> i) & 1u;
}
template <class T, class = std::enable_if_t<std::is_integral_v<T>>>
void set_bit(T& port, int i, bool value) {
  const auto one = static_cast<T>(T{1} << i);
  port = value ? static_cast<T>(port | one) : static_cast<T>(port & ~one);
}

// Field k (of `bits` bits) of a port holding three: written, and read signed or not.
template <class Port>
void put(Port& port, int k, int bits, int64_t value) {
  for (int i = 0; i < bits; ++i) set_bit(port, k * bits + i, (static_cast<uint64_t>(value) >> i) & 1u);
}
template <class Port>
int64_t field(const Port& port, int k, int bits, bool is_signed = true) {
  uint64_t value = 0;
  for (int i = 0; i < bits; ++i) value |= uint64_t{bit(port, k * bits + i)} << i;
  if (!is_signed || bits == 64) return static_cast<int64_t>(value);
  return static_cast<int64_t>(value << (64 - bits)) >> (64 - bits);
}

std::vector<UnitTriangle> triangles(std::mt19937_64& rng, const Widths& w, int count) {
  std::vector<UnitTriangle> out;
  for (int n = 0; n < count; ++n) {
    cdsim::ScreenTriangle s = cdsim::testing::random_triangle(rng, kWidth, kHeight, 30.0, 400.0);
    if (n % 7 == 3)  // far off the viewport on one side
      for (auto& v : s.vertex) v.x = v.x * 3 - 2 * kWidth;
    if (n % 11 == 5)  // flat: u is affine, nothing splits
      for (auto& v : s.vertex) v.w = 2.0;
    if (n % 13 == 6) s.vertex[2] = s.vertex[1];  // zero area
    out.push_back(cdsim::to_unit(s, w, static_cast<size_t>(n)));
  }
  return out;
}

template <class Dut>
uint64_t check_adaptive_split(const Options& options, const std::string& name, int subpixel_bits,
                              int uv_in_frac, int q_bits, int recip_bits, int recip_latency, int depth,
                              int bound_frac, int uv_extra) {
  Widths w;
  w.subpixel_bits = subpixel_bits;
  w.uv_in_frac = uv_in_frac;
  w.q_bits = q_bits;
  w.recip_bits = recip_bits;
  w.recip_latency = recip_latency;
  w.adapt_depth = depth;
  w.adapt_bound_frac = bound_frac;
  w.adapt_uv_extra = uv_extra;
  const Widths leaf = cdsim::adaptive_leaf_widths(w);
  const int coord_bits = 16 + subpixel_bits, uv_bits = 16 + uv_in_frac;
  const int leaf_coord_bits = 16 + leaf.subpixel_bits, leaf_uv_bits = 16 + leaf.uv_in_frac;
  std::printf("%s: seed=%" PRIu64 "\n", name.c_str(), options.seed);
  std::fflush(stdout);
  std::mt19937_64 rng(options.seed * 1000003 + static_cast<uint64_t>(depth * 100 + bound_frac));
  const std::vector<UnitTriangle> input = triangles(rng, w, 300);
  Bench<Dut> bench(options, name);
  Dut& dut = bench.dut();
  Failures failures(name, options.seed);
  dut.viewport_width_i = kWidth;
  dut.viewport_height_i = kHeight;
  dut.tri_valid_i = 0;
  dut.leaf_ready_i = 0;
  dut.hold_i = 0;  // the unit's hold: checked in the adaptive unit's regressions
  dut.rst_ni = 0;
  bench.tick();
  dut.rst_ni = 1;

  std::bernoulli_distribution ready(0.7);
  uint64_t leaves = 0, splits = 0, dropped = 0;
  int64_t free_from = static_cast<int64_t>(bench.cycle());  // the engine can accept from here
  for (size_t t = 0; t < input.size() && failures.count() == 0; ++t) {
    const AdaptiveSplit split = cdsim::adaptive_split(input[t], w, kWidth, kHeight);
    if (std::getenv("TB_TRACE")) {
      std::printf("triangle %zu: accept %" PRId64 ", %zu leaves, splits %" PRId64 ", dropped %" PRId64 ", tail %" PRId64 ":", t,
                  free_from, split.leaves.size(), split.splits, split.dropped, cdsim::split_engine_cycles(split.tail, w));
      for (const AdaptiveLeaf& l : split.leaves) std::printf(" d%d+%" PRId64, l.depth, cdsim::split_engine_cycles(l.work, w));
      std::printf("\n");
    }
    splits += static_cast<uint64_t>(split.splits);
    dropped += static_cast<uint64_t>(split.dropped);
    for (size_t k = 0; k < 3; ++k) {
      const cdsim::UnitVertex& v = input[t].vertex[k];
      put(dut.tri_x_i, static_cast<int>(k), coord_bits, v.x);
      put(dut.tri_y_i, static_cast<int>(k), coord_bits, v.y);
      put(dut.tri_q_i, static_cast<int>(k), 32, v.q_float);
      put(dut.tri_u_i, static_cast<int>(k), uv_bits, v.u);
      put(dut.tri_v_i, static_cast<int>(k), uv_bits, v.v);
    }
    dut.tri_valid_i = 1;
    bench.settle();
    const int64_t accept_expected = free_from;
    while (!dut.tri_ready_o && static_cast<int64_t>(bench.cycle()) < accept_expected + 4) bench.tick();
    if (static_cast<int64_t>(bench.cycle()) != accept_expected || !dut.tri_ready_o) {
      failures.report(format("triangle %zu accepted in cycle %" PRIu64 ", expected %" PRId64, t, bench.cycle(),
                             accept_expected));
      break;
    }
    bench.tick();  // the accept cycle
    dut.tri_valid_i = 0;
    int64_t from = accept_expected + cdsim::kAdaptiveIntakeCycles;
    for (size_t i = 0; i < split.leaves.size(); ++i) {
      const AdaptiveLeaf& l = split.leaves[i];
      const int64_t offer = from + cdsim::split_engine_cycles(l.work, w);
      // Nothing offered before its cycle.
      while (static_cast<int64_t>(bench.cycle()) < offer) {
        dut.leaf_ready_i = ready(rng);
        bench.settle();
        if (dut.leaf_valid_o) {
          failures.report(format("triangle %zu leaf %zu offered in cycle %" PRIu64 ", expected %" PRId64, t, i,
                                 bench.cycle(), offer));
          break;
        }
        bench.tick();
      }
      if (failures.count() != 0) break;
      dut.leaf_ready_i = ready(rng);
      bench.settle();
      if (!dut.leaf_valid_o) {
        failures.report(format("triangle %zu leaf %zu not offered in cycle %" PRId64, t, i, offer));
        break;
      }
      const auto expect = [&](const char* field, int64_t got, int64_t want) {
        if (got != want)
          failures.report(format("triangle %zu leaf %zu (of %zu, depth %d): %s = %" PRId64 ", model %" PRId64, t, i,
                                 split.leaves.size(), l.depth, field, got, want));
      };
      for (size_t k = 0; k < 3; ++k) {
        const cdsim::UnitVertex& v = l.triangle.vertex[k];
        const int ki = static_cast<int>(k);
        expect("x", field(dut.leaf_x_o, ki, leaf_coord_bits), v.x);
        expect("y", field(dut.leaf_y_o, ki, leaf_coord_bits), v.y);
        expect("q", field(dut.leaf_q_o, ki, 32, false), v.q_float);
        expect("u", field(dut.leaf_u_o, ki, leaf_uv_bits), v.u);
        expect("v", field(dut.leaf_v_o, ki, leaf_uv_bits), v.v);
      }
      expect("depth", dut.leaf_depth_o, l.depth);
      // Held until taken.
      while (!dut.leaf_ready_i) {
        bench.tick();
        dut.leaf_ready_i = ready(rng);
        bench.settle();
        if (!dut.leaf_valid_o) {
          failures.report(format("triangle %zu leaf %zu dropped before it was taken", t, i));
          break;
        }
      }
      from = static_cast<int64_t>(bench.cycle()) + 1;
      bench.tick();
      dut.leaf_ready_i = 0;
      ++leaves;
    }
    free_from = from + cdsim::split_engine_cycles(split.tail, w);
    // Done in the cycle the engine can take the next triangle.
    while (static_cast<int64_t>(bench.cycle()) < free_from) {
      bench.settle();
      if (dut.tri_done_o) failures.report(format("triangle %zu done in cycle %" PRIu64 ", expected %" PRId64, t,
                                                 bench.cycle(), free_from));
      bench.tick();
    }
    bench.settle();
    const uint32_t flags = (split.flags & cdsim::flag::kDepthRange ? 1u : 0u) |
                           (split.flags & cdsim::flag::kOutputSaturated ? 2u : 0u);
    if (!dut.tri_done_o || dut.tri_flags_o != flags)
      failures.report(format("triangle %zu: done %d, flags %d in cycle %" PRId64 ", model flags %u", t, dut.tri_done_o,
                             dut.tri_flags_o, free_from, flags));
  }
  failures.summary();
  std::printf("%s: %zu triangles, %" PRIu64 " leaves, %" PRIu64 " splits, %" PRIu64 " dropped, %" PRIu64
              " cycles, %" PRIu64 " mismatches\n",
              name.c_str(), input.size(), leaves, splits, dropped, bench.cycle(), failures.count());
  if (failures.count() == 0 && (splits == 0 || leaves < input.size())) {
    std::printf("FAIL %s: the triangles did not exercise splits\n", name.c_str());
    return 1;
  }
  return failures.count();
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse_options(argc, argv);
  uint64_t failed = 0;
  bool matched = false;
#define RUN_CONFIG(Prefix, config_name, ...)                                            \
  if (options.only.empty() || options.only == config_name) {                            \
    matched = true;                                                                     \
    failed += check_adaptive_split<Prefix>(options, config_name, __VA_ARGS__) ? 1 : 0;  \
  }
  ADAPTIVE_SPLIT_CONFIGS(RUN_CONFIG)
#undef RUN_CONFIG
  if (!matched) {
    std::fprintf(stderr, "--only %s: no such configuration\n", options.only.c_str());
    return 2;
  }
  return failed == 0 ? 0 : 1;
}
