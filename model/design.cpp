#include "design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>

#include "widths.hpp"

namespace cdsim {

namespace {

std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// A row's set names, each replaced by its set's words.
std::vector<std::string> expand(const std::map<std::string, std::string>& sets, const char* names,
                                const char* what, const char* design) {
  std::vector<std::string> out;
  for (const std::string& name : words(names)) {
    const auto it = sets.find(name);
    if (it == sets.end())
      throw std::logic_error(fmt::format("designs.def: design {} names no {} set {}", design, what, name));
    for (std::string& w : words(it->second)) out.push_back(std::move(w));
  }
  return out;
}

std::vector<Design> design_table() {
  const std::map<std::string, std::string> width_sets = {
#define CDSIM_WIDTH_SET(set, widths) {#set, widths},
#define CDSIM_AXIS_SET(set, axes)
#define CDSIM_DESIGN(...)
#include "designs.def"
#undef CDSIM_DESIGN
#undef CDSIM_AXIS_SET
#undef CDSIM_WIDTH_SET
  };
  const std::map<std::string, std::string> axis_sets = {
#define CDSIM_WIDTH_SET(set, widths)
#define CDSIM_AXIS_SET(set, axes) {#set, axes},
#define CDSIM_DESIGN(...)
#include "designs.def"
#undef CDSIM_DESIGN
#undef CDSIM_AXIS_SET
#undef CDSIM_WIDTH_SET
  };
  std::vector<Design> designs;
  const auto add = [&](const char* name, Design::Kind kind, int density, bool correction, bool pipelined,
                       int subdivision, bool persp, bool quadratic, bool fallback, const char* sized,
                       const char* sweep, bool sweep_grid, const char* summary) {
    Design d;
    d.name = name;
    d.kind = kind;
    d.density = density;
    d.correction = correction;
    d.pipelined = pipelined;
    d.subdivision = subdivision;
    d.summary = summary;
    d.persp = persp;
    d.quadratic = quadratic;
    d.fallback = fallback;
    d.sized_widths = expand(width_sets, sized, "width", name);
    for (const std::string& width : d.sized_widths)
      if (std::none_of(param_table().begin(), param_table().end(),
                       [&](const ParamInfo& p) { return width == p.name; }))
        throw std::logic_error(fmt::format("designs.def: design {} sizes {}, which widths.def lacks", name, width));
    d.sweep_axes = expand(axis_sets, sweep, "axis", name);
    d.sweep_grid = sweep_grid;
    designs.push_back(std::move(d));
  };
#define CDSIM_WIDTH_SET(set, widths)
#define CDSIM_AXIS_SET(set, axes)
#define CDSIM_DESIGN(name, kind, ...) add(name, Design::Kind::kind, __VA_ARGS__);
#include "designs.def"
#undef CDSIM_DESIGN
#undef CDSIM_AXIS_SET
#undef CDSIM_WIDTH_SET
  return designs;
}

}  // namespace

const char* kind_name(Design::Kind kind) {
  switch (kind) {
    case Design::Kind::ConstantDepth: return "constant_depth";
    case Design::Kind::Divide: return "divide";
    case Design::Kind::Kim: return "kim";
    case Design::Kind::Affine: return "affine";
    case Design::Kind::Adaptive: return "adaptive";
  }
  return "unknown";
}

const std::vector<Design>& all_designs() {
  static const std::vector<Design> designs = design_table();
  return designs;
}

RtlTop rtl_top(const Design& design) {
  return design.kind == Design::Kind::Adaptive ? RtlTop::AdaptiveUnit : RtlTop::ScanUnit;
}

bool has_rtl(const Design& design) {
  switch (design.kind) {
    case Design::Kind::ConstantDepth:
    case Design::Kind::Divide:
    case Design::Kind::Kim:
    case Design::Kind::Affine:
    case Design::Kind::Adaptive: return true;
  }
  return false;
}

std::string rtl_design_names() {
  std::string names;
  for (const auto& d : all_designs())
    if (has_rtl(d)) names += (names.empty() ? "" : ", ") + d.name;
  return names;
}

std::vector<UnitParameter> unit_parameters(const std::vector<const Design*>& designs) {
  int density_log2 = 0, segment_log2 = 0;
  bool correction = false, table = false, divide = false, affine = false, affine_sub = false;
  bool kim_iter = false, kim_pipe = false, persp = false, quad_sub = false;
  for (const Design* d : designs) {
    switch (d->kind) {
      case Design::Kind::ConstantDepth:
        table = true;
        density_log2 = std::max(density_log2, log2_ceil(d->density));
        correction = correction || d->correction;
        persp = persp || d->persp;
        divide = divide || d->fallback;
        break;
      case Design::Kind::Divide: divide = true; break;
      case Design::Kind::Kim: (d->pipelined ? kim_pipe : kim_iter) = true; break;
      case Design::Kind::Affine:
        if (d->subdivision == 0) {
          affine = true;
        } else {
          (d->quadratic ? quad_sub : affine_sub) = true;
          segment_log2 = std::max(segment_log2, log2_ceil(d->subdivision));
        }
        break;
      case Design::Kind::Adaptive: affine = true; break;  // the unit behind its split engine
    }
  }
  if (!affine_sub && !quad_sub) segment_log2 = 5;  // the unit's default; nothing uses it
  return {{"MaxDensityLog2", density_log2}, {"HasCorrection", correction}, {"HasPersp", persp},
          {"HasTable", table},              {"HasDivide", divide},
          {"HasAffine", affine},            {"HasAffineSub", affine_sub},
          {"HasQuadSub", quad_sub},         {"MaxSegmentLog2", segment_log2}, {"HasKimIter", kim_iter},
          {"HasKimPipe", kim_pipe}};
}

std::string unit_parameter_list(const std::vector<UnitParameter>& parameters) {
  std::string list;
  for (const UnitParameter& p : parameters) list += fmt::format("{}{}={}", list.empty() ? "" : " ", p.name, p.value);
  return list;
}

const Design& find_design(const std::string& name) {
  for (const auto& d : all_designs())
    if (d.name == name) return d;
  std::string known;
  for (const auto& d : all_designs()) known += " " + d.name;
  throw std::invalid_argument(fmt::format("unknown design '{}'; known:{}", name, known));
}

std::vector<Design> parse_design_list(const std::string& list) {
  if (list.empty()) return all_designs();
  std::vector<Design> out;
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = list.find(',', start);
    const std::string name = list.substr(start, comma == std::string::npos ? comma : comma - start);
    out.push_back(find_design(name));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace cdsim
