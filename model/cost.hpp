// Register-bit accounting, the same rules for every design (docs/designs.md):
// the per-triangle state the setup hands on, the walker's and datapath's
// per-pixel registers, and pipeline stages. Table SRAM is counted separately.
#pragma once

#include <cstdint>

#include "design.hpp"
#include "widths.hpp"

namespace cdsim {

int64_t register_bits(const Design& design, const Widths& widths);

}  // namespace cdsim
