#include "widths.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <map>
#include <stdexcept>

namespace cdsim {

const std::vector<ParamInfo>& param_table() {
  static const std::vector<ParamInfo> table = {
#define CDSIM_PARAM(name, def, lo, hi, doc) {#name, def, lo, hi, doc, &Widths::name},
#include "widths.def"
#undef CDSIM_PARAM
  };
  return table;
}

void set_param(Widths& widths, const std::string& name, long long value) {
  const auto& table = param_table();
  const auto it = std::find_if(table.begin(), table.end(),
                               [&](const ParamInfo& p) { return name == p.name; });
  if (it == table.end()) {
    std::string known;
    for (const auto& p : table) known += fmt::format(" {}", p.name);
    throw std::invalid_argument(fmt::format("unknown parameter '{}'; known:{}", name, known));
  }
  if (value < it->min_value || value > it->max_value)
    throw std::invalid_argument(fmt::format("parameter {}={} is out of range [{}, {}] ({})", name,
                                            value, it->min_value, it->max_value, it->meaning));
  widths.*(it->field) = static_cast<int>(value);
}

void apply_setting(Widths& widths, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw std::invalid_argument(
        fmt::format("setting '{}' is not of the form NAME=VALUE", assignment));
  const std::string name = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  // Plain decimal: no spaces, '+', hex or exponent.
  long long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error == std::errc::invalid_argument || end != text.data() + text.size())
    throw std::invalid_argument(
        fmt::format("setting '{}': value '{}' is not an integer", assignment, text));
  if (error == std::errc::result_out_of_range)
    throw std::invalid_argument(fmt::format("setting '{}': value {} is out of range", assignment, text));
  set_param(widths, name, value);
}

void apply_settings(Widths& widths, const std::vector<std::string>& assignments) {
  std::map<std::string, std::string> seen;  // parameter -> its setting
  for (const std::string& assignment : assignments) {
    apply_setting(widths, assignment);
    const std::string name = assignment.substr(0, assignment.find('='));
    const auto [it, fresh] = seen.emplace(name, assignment);
    if (!fresh)
      throw std::invalid_argument(fmt::format(
          "--set {} and --set {} both set parameter {}; give it once", it->second, assignment, name));
  }
}

void validate(const Widths& w) {
  // The model's walker accumulates T + o*S (column_walker.hpp, walker_bits)
  // in 64 bits where that suffices, else in 128; the correction's product
  // of the weight and a difference of two such values must fit 127 bits.
  const int frac = std::max(w.t_frac, w.s_frac);
  const int beyond = std::max(0, w.out_frac - frac);
  const int acc_bits = std::max(w.t_int + frac, w.s_int + frac + 14) + 2 + beyond;
  if (acc_bits + w.d_frac + 2 > 127) {
    const int t_int_max = 125 - w.d_frac - 2 - frac - beyond, s_int_max = t_int_max - 14;
    throw std::invalid_argument(fmt::format(
        "widths t_int={} s_int={} t_frac={} s_frac={} out_frac={} need a {}-bit walker accumulator "
        "(t_int, or s_int + 14 for 2^14 columns, + max(t_frac, s_frac) + 2, + out_frac beyond that); "
        "with d_frac={} the model's limit is {} bits: t_int at most {} and s_int at most {} here "
        "(cdsim widths lists each parameter's limit at the others' values)",
        w.t_int, w.s_int, w.t_frac, w.s_frac, w.out_frac, acc_bits, w.d_frac, 125 - w.d_frac, t_int_max,
        s_int_max));
  }
  if (w.persp_table_log2 > w.persp_frac)
    throw std::invalid_argument(fmt::format(
        "persp_table_log2={} needs persp_frac >= it (persp_frac={}): the table's index is the top "
        "bits of the fraction",
        w.persp_table_log2, w.persp_frac));
  // Edge functions of the adaptive design's leaves are 64-bit: coordinates
  // below 2^(15 + subpixel bits) each way.
  if (w.subpixel_bits + w.adapt_depth > 14)
    throw std::invalid_argument(fmt::format(
        "subpixel_bits + adapt_depth = {} exceeds 14: the leaves' vertices would carry more subpixel bits "
        "than the edge functions hold",
        w.subpixel_bits + w.adapt_depth));
  if (w.setup_product_register && w.setup_multipliers > 0)
    throw std::invalid_argument(fmt::format(
        "setup_product_register=1 needs setup_multipliers=0 (setup_multipliers={}): shared multipliers "
        "register their results already",
        w.setup_multipliers));
  if (w.out_int + w.out_frac > 48)
    throw std::invalid_argument("out_int + out_frac must not exceed 48 bits");
}

std::string describe(const Widths& widths) {
  std::string out;
  for (const auto& p : param_table()) {
    if (!out.empty()) out += ' ';
    out += fmt::format("{}={}", p.name, widths.*(p.field));
  }
  return out;
}

Widths adaptive_leaf_widths(const Widths& widths) {
  Widths leaf = widths;
  leaf.subpixel_bits += widths.adapt_depth;
  leaf.uv_in_frac += widths.adapt_uv_extra;
  return leaf;
}

}  // namespace cdsim
