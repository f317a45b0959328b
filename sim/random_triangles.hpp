// Seeded random unit triangles for the RTL regression, mixed with the hard
// cases of SPEC §9 that are legal unit inputs.
#pragma once

#include <cstdint>
#include <vector>

#include "scoreboard.hpp"

namespace cdsim::rtl {

// designs: one per job in turn. Most jobs use a small viewport to stay fast.
std::vector<Job> random_jobs(size_t count, uint64_t seed, const Widths& widths,
                             const std::vector<const Design*>& designs);

}  // namespace cdsim::rtl
