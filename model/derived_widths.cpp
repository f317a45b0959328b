#include "derived_widths.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "design.hpp"
#include "setup_schedule.hpp"

namespace cdsim {

namespace {

int ceil_div_int(int a, int b) { return (a + b - 1) / b; }

int bits_for_unsigned(long long value) {
  int bits = 1;
  while ((1LL << bits) <= value) ++bits;
  return bits;
}

}  // namespace

// The bounds behind each formula are in docs/rtl.md ("Derived widths"). Where a
// magnitude is bounded by 2^k, a signed width is k + 1.
DerivedWidths derive(const Widths& w) {
  DerivedWidths d;
  const int sp = w.subpixel_bits;
  d.coord_bits = 16 + sp;               // |x| < 2^(15 + sp)
  d.uv_bits = 16 + w.uv_in_frac;        // |u| < 2^(15 + uv_in_frac)
  d.diff_bits = d.coord_bits + 1;       // |dx| < 2^(16 + sp)
  d.det_bits = 2 * d.diff_bits;         // |det| < 2 * 2^(2 (16 + sp))
  d.edge_c_bits = d.diff_bits + d.coord_bits;
  d.pixel_bits = 13;                    // viewport <= 8192
  d.q_vertex_bits = w.q_bits + 1;       // round to nearest can reach 2^q_bits
  d.attr_q_bits = w.q_bits + 2;
  d.attr_uv_bits = d.q_vertex_bits + d.uv_bits;
  // |dA| <= 2^A for an attribute of A bits; two products with |dy| < 2^(diff - 1).
  d.coef_q_bits = d.attr_q_bits + d.diff_bits + 1;
  d.coef_uv_bits = d.attr_uv_bits + d.diff_bits + 1;
  // A0 det + coef_x ref_x + coef_y ref_y, |ref| < 2^(diff - 1).
  d.exact_ref_q_bits =
      std::max(d.attr_q_bits + d.det_bits - 2, d.coef_q_bits + d.diff_bits - 2) + 3;
  d.exact_ref_uv_bits =
      std::max(d.attr_uv_bits + d.det_bits - 2, d.coef_uv_bits + d.diff_bits - 2) + 3;
  d.peak_bits = d.q_vertex_bits + d.det_bits - 1;
  d.shift_bits = bits_for_unsigned(std::max(w.plane_bits, d.peak_bits - w.plane_bits)) + 1;
  // After the shift q_max |det| < 2^plane_bits; a plane value at the box corner
  // extrapolates by at most (|det| + 2^(2 diff)) / |det| (slivers), a step by
  // 2^(diff + sp) / |det|. U and V carry |u| < 2^(uv_bits - 1) more.
  d.plane_ref_q_bits = w.plane_bits + 2 * d.diff_bits + 2;
  d.plane_ref_uv_bits = w.plane_bits + d.uv_bits + 2 * d.diff_bits + 2;
  d.plane_step_q_bits = w.plane_bits + d.diff_bits + sp + 2;
  d.plane_step_uv_bits = w.plane_bits + d.uv_bits + d.diff_bits + sp + 2;
  d.step_uv_bits = d.plane_step_uv_bits + 1;  // |g| <= 1
  d.g_bits = w.g_frac + 2;
  // m ((minor - minor_ref) 2^g_frac - g (major - major_ref)), offsets < 2^diff.
  d.kappa_bits = d.diff_bits + w.g_frac + 5;
  d.line_bits = 18;  // |line| <= m (box height + box width) <= 2^16
  d.line_phase_frac = w.line_phase_frac();
  d.exact_shift_bits = w.g_frac + 16;  // |m g o| <= 4 2^g_frac 8191
  d.t_dist_bits = w.g_frac + 1;        // |t| <= 2^(g_frac - 1)
  d.weight_bits = w.d_frac;            // weight <= 2^(d_frac - 1)
  // E = fixed (major 2^sp + half) + free half + c - threshold over the box.
  d.edge_n_bits = d.edge_c_bits + 2;
  d.edge_step_bits = d.diff_bits - 1 + sp;
  d.edge_bound_bits = d.edge_n_bits - sp + 1;
  d.edge_slope_bits = d.diff_bits + 1;
  // Lines reach k = +-2^16 from the reference: one more offset of 2^(diff - 1).
  d.fill_q_bits = d.plane_ref_q_bits + 2;
  d.fill_uv_bits = d.plane_ref_uv_bits + 2;
  // A pixel of the box lies inside the lines' reach, so the fill's bound holds.
  d.pixel_q_bits = d.fill_q_bits;
  d.pixel_uv_bits = d.fill_uv_bits;
  d.exponent_bits = bits_for_unsigned(d.fill_q_bits - 1);
  d.t_bits = w.t_int + w.t_frac;
  d.s_bits = w.s_int + w.s_frac;
  d.word_bits = 2 * d.t_bits + 2 * d.s_bits + 2;
  d.eps_bits = w.eps_int + w.eps_frac;
  d.persp_word_bits = d.word_bits + d.eps_bits + 1;
  d.line_value_frac = std::max(w.t_frac, w.s_frac);
  d.line_value_bits = std::max(d.t_bits + d.line_value_frac - w.t_frac,
                               d.s_bits + d.line_value_frac - w.s_frac + d.pixel_bits) +
                      1;
  d.corrected_bits = d.line_value_bits + 2;
  d.out_bits = w.out_int + w.out_frac;
  // Serial dividers: |g| 2^g_frac <= 2^g_frac; a span end needs edge_bound_bits;
  // its step per column |fixed / free| < 2^(diff - 1).
  d.g_div_quotient_bits = w.g_frac + 1;
  d.bound_div_quotient_bits = d.edge_bound_bits - 1;
  d.slope_div_quotient_bits = d.diff_bits - 1;
  d.div_cycles = ceil_div_int(
      std::max({d.g_div_quotient_bits, d.bound_div_quotient_bits, d.slope_div_quotient_bits}),
      w.div_bits_per_cycle);
  const SetupSchedule schedule = setup_schedule(w, d);
  d.setup_stage_a = schedule.stage_cycle[0];
  d.setup_stage_b = schedule.stage_cycle[1];
  d.setup_stage_c = schedule.stage_cycle[2];
  d.setup_div_done = schedule.div_done;
  d.setup_stage_d = schedule.stage_cycle[3];
  d.setup_stage_e = schedule.stage_cycle[4];
  d.setup_cycles = schedule.setup_cycles;
  d.setup_count_bits = bits_for_unsigned(d.setup_cycles - 1);
  d.fill_latency = w.recip_latency + w.fill_product_register;
  d.setup_operand_a_bits = schedule.operand_a_bits;
  d.setup_operand_b_bits = schedule.operand_b_bits;
  d.setup_acc_bits = schedule.acc_bits;
  // affine's planes of u and v: a value at a pixel is the reference plus up to
  // 2^13 steps along each axis; its dividers (t_bits or s_bits quotients) resolve
  // enough bits a cycle to finish with the others (at most 58 / 5 = 12).
  d.affine_ref_bits = w.t_int + w.s_frac;
  d.affine_acc_bits = std::max(d.affine_ref_bits, d.s_bits + 14) + 2;
  d.affine_div_bits_per_cycle = ceil_div_int(std::max(d.affine_ref_bits, d.s_bits), d.div_cycles);
  d.cycle_count_bits = 32;
  return d;
}

const std::vector<DerivedInfo>& derived_table() {
  static const std::vector<DerivedInfo> table = {
#define CDSIM_DERIVED(name, doc) {#name, doc, &DerivedWidths::name},
#include "derived_widths.def"
#undef CDSIM_DERIVED
  };
  return table;
}

std::string rtl_header(const Widths& w, const std::string& config) {
  const DerivedWidths d = derive(w);
  std::string out = fmt::format(
      "// Generated by `cdsim widths --sv` from model/widths.def (width configuration '{}').\n"
      "// Do not edit: change model/widths.def, model/derived_widths.cpp or the configuration.\n"
      "// {}\n"
      "`ifndef CD_WIDTHS_SVH\n`define CD_WIDTHS_SVH\n`define CD_WIDTHS_CONFIG \"{}\"\n",
      config, describe(w), config);
  const auto upper = [](std::string s) {
    for (char& c : s) c = static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    return s;
  };
  out += "// Parameters (widths.def)\n";
  for (const auto& p : param_table())
    out += fmt::format("`define CD_{} {}\n", upper(p.name), w.*(p.field));
  out += "// Derived widths and cycle budgets (derived_widths.cpp)\n";
  for (const auto& p : derived_table())
    out += fmt::format("`define CD_{} {}  // {}\n", upper(p.name), d.*(p.field), p.meaning);
  out += "// Encodings (model/encodings.def)\n";
  out += encoding::rtl_defines();
  out += "// Table word, from bit 0: T.u, T.v, S.u, S.v, table_saturated, depth_range\n";
  out += fmt::format("`define CD_WORD_TU_LSB {}\n", 0);
  out += fmt::format("`define CD_WORD_TV_LSB {}\n", d.t_bits);
  out += fmt::format("`define CD_WORD_SU_LSB {}\n", 2 * d.t_bits);
  out += fmt::format("`define CD_WORD_SV_LSB {}\n", 2 * d.t_bits + d.s_bits);
  out += fmt::format("`define CD_WORD_SATURATED_BIT {}\n", 2 * d.t_bits + 2 * d.s_bits);
  out += fmt::format("`define CD_WORD_DEPTH_RANGE_BIT {}\n", 2 * d.t_bits + 2 * d.s_bits + 1);
  out += "// cd-persp's word goes on: eps, eps_saturated (persp_word_bits in all)\n";
  out += fmt::format("`define CD_WORD_EPS_LSB {}\n", d.word_bits);
  out += fmt::format("`define CD_WORD_EPS_SATURATED_BIT {}\n", d.word_bits + d.eps_bits);
  out += setup_schedule_defines(setup_schedule(w, d));
  out += "`endif\n";
  return out;
}

namespace {

bool fits_signed(fx::Wide raw, int bits) {
  if (bits >= 127) return true;
  const fx::Wide limit = fx::Wide{1} << (bits - 1);
  return raw >= -limit && raw < limit;
}

__extension__ typedef unsigned __int128 UnsignedWide;

std::string wide_text(fx::Wide raw) {
  const bool negative = raw < 0;
  UnsignedWide magnitude = negative ? -static_cast<UnsignedWide>(raw) : static_cast<UnsignedWide>(raw);
  std::string digits;
  do {
    digits.insert(digits.begin(), static_cast<char>('0' + static_cast<int>(magnitude % 10)));
    magnitude /= 10;
  } while (magnitude != 0);
  return negative ? "-" + digits : digits;
}

}  // namespace

void fits_or_throw(fx::Wide raw, int bits, const char* what) {
  if (!fits_signed(raw, bits))
    throw std::logic_error(fmt::format("derived width too narrow: {} = {} needs more than {} bits",
                                       what, wide_text(raw), bits));
}

void fits_unsigned_or_throw(fx::Wide raw, int bits, const char* what) {
  if (raw < 0 || (bits < 127 && raw >= (fx::Wide{1} << bits)))
    throw std::logic_error(fmt::format(
        "derived width too narrow: {} = {} is not an unsigned {}-bit value", what, wide_text(raw),
        bits));
}

}  // namespace cdsim
