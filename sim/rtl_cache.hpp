// The RTL verilated for any widths (`cdsim regress --set`, `cdsim size
// --verify`): built on first use into a cache folder, as a shared object that
// holds the Verilated model and the bench of bench.hpp instantiated for it, and
// loaded into cdsim. rtl_cache.cpp describes the cache.
#pragma once

#include <string>
#include <vector>

#include "design.hpp"
#include "scoreboard.hpp"
#include "widths.hpp"

namespace cdsim::rtl {

struct BenchOptions;

// run_bench<Dut> (bench.hpp) for the cached model.
using RunBench = int (*)(const std::vector<Job>* jobs, const Widths* widths,
                         const BenchOptions* options);

// Verilates and compiles the RTL for exactly these widths into cache_dir
// (empty: default_rtl_cache_dir()) on first use, saying what it does; later
// calls reuse it, once its files match the manifests written when it was built
// (an entry that does not is said, naming it, and rebuilt). Throws
// std::runtime_error naming the log when Verilator or the compiler fails, and
// Interrupted (having stopped them) on SIGINT or SIGTERM.
// A coverage build is verilated with Verilator's coverage points and the user
// cover points of sim/cover/cd_scan_cover.sv, and cached apart: All has line,
// branch and toggle points; Lines leaves out toggle points, which makes the
// build and the run several times faster.
enum class CoverageBuild { None, Lines, All };
// `adaptive`: the adaptive design's unit (rtl/adaptive_unit.sv), whose header
// is its leaf unit's. `parameters`: the scan unit's Has*/Max* parameters
// (unit_parameters, model/design.hpp) for a unit that holds only the chosen
// designs' hardware, as `cdsim area` synthesises it; empty for every design's.
RunBench load_custom_rtl(const Widths& widths, const std::string& cache_dir,
                         CoverageBuild coverage = CoverageBuild::None, bool adaptive = false,
                         const std::vector<UnitParameter>& parameters = {});

// Runs one tool (argv[0] looked up on PATH), its output to `log`; throws
// naming `what`, the exit status and the log's first lines when it fails.
void run_tool(const std::vector<std::string>& argv, const std::string& log, const std::string& what);

// $XDG_CACHE_HOME/cdsim/rtl, else ~/.cache/cdsim/rtl (cache_files.hpp, cache_root).
std::string default_rtl_cache_dir();

}  // namespace cdsim::rtl
