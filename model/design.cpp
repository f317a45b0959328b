#include "design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace cdsim {

const std::vector<Design>& all_designs() {
  using K = Design::Kind;
  static const std::vector<Design> designs = {
      {"cd-none", K::ConstantDepth, 1, false, false, 0, "constant-depth lines, no correction"},
      {"cd-linear", K::ConstantDepth, 1, true, false, 0, "constant-depth lines, linear correction"},
      {"cd-dense2", K::ConstantDepth, 2, false, false, 0, "2 lines per pixel, no correction"},
      {"cd-dense4", K::ConstantDepth, 4, false, false, 0, "4 lines per pixel, no correction"},
      {"cd-dense2-linear", K::ConstantDepth, 2, true, false, 0, "2 lines per pixel, linear correction"},
      {"cd-persp", K::ConstantDepth, 1, true, false, 0,
       "constant-depth lines, perspective-correct correction (eps per line, a small 1/(1+x) table)", true},
      {"cd-linear-div", K::ConstantDepth, 1, true, false, 0,
       "cd-linear, and divide's per-pixel datapath for triangles near their horizon", false, false, true},
      {"cd-persp-div", K::ConstantDepth, 1, true, false, 0,
       "cd-persp, and divide's per-pixel datapath for triangles near their horizon", true, false, true},
      {"divide", K::Divide, 1, false, false, 0, "exact per-pixel reciprocal, one pixel per clock"},
      {"kim-iter", K::Kim, 1, false, false, 0,
       "Kim-style: midpoint integer part, iterative restoring-division fraction (reconstruction)"},
      {"kim-pipe", K::Kim, 1, false, true, 0,
       "Kim-style: midpoint integer part, pipelined restoring-division fraction (reconstruction)"},
      {"affine-sub16", K::Affine, 1, false, false, 16, "exact divide every 16 pixels, affine between"},
      {"affine-sub8", K::Affine, 1, false, false, 8, "exact divide every 8 pixels, affine between"},
      {"quad-sub16", K::Affine, 1, false, false, 16,
       "exact divide at the start, middle and end of every 16-pixel segment, quadratic between", false, true},
      {"quad-sub8", K::Affine, 1, false, false, 8,
       "exact divide at the start, middle and end of every 8-pixel segment, quadratic between", false, true},
      {"quad-sub32", K::Affine, 1, false, false, 32,
       "exact divide at the start, middle and end of every 32-pixel segment, quadratic between", false, true},
      {"adaptive", K::Adaptive, 1, false, false, 0,
       "Kamen & Shirman: split in four at edge midpoints while the edge error exceeds a bound, affine per leaf"},
      {"affine", K::Affine, 1, false, false, 0, "plain affine interpolation of u, v (not perspective-correct)"},
  };
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
