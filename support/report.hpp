// Human-readable tables and JSON for results; every report names the scene,
// the widths, the seed and the build so that a figure can be made again.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "evaluate.hpp"

namespace cdsim {

std::string build_id();  // git revision, compiler and build type
std::string provenance(const Scene& scene, const Widths& widths);
std::string worst_pixels(const std::vector<DesignResult>& results, const Scene& scene,
                         const Widths& widths);
std::string results_table(const std::vector<DesignResult>& results, const Widths& widths);
// Where each design's cycles go: setup, table fill and walk (the unit runs
// them one after another, triangle after triangle; docs/rtl.md), with pixels
// per triangle, the figure that decides how far from one pixel per clock a
// scene of small triangles stays.
std::string cycle_breakdown_table(const std::vector<DesignResult>& results);
nlohmann::json results_json(const Scene& scene, const Widths& widths,
                            const std::vector<DesignResult>& results);

}  // namespace cdsim
