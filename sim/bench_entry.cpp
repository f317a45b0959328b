// The bench of bench.hpp for RTL that `cdsim regress --set` verilates into its
// cache (rtl_cache.cpp). Not part of the cdsim build: the cache compiles it
// against the generated model Vcd_scan_unit_custom and links both into a
// shared object that cdsim loads. The object takes the SystemC kernel, the
// Verilator runtime and the model code from cdsim itself (cdsim exports its
// symbols), so it holds none of them.
#include "Vcd_scan_unit_custom.h"
#include "bench.hpp"

extern "C" int cdsim_rtl_run_bench(const std::vector<cdsim::rtl::Job>* jobs,
                                   const cdsim::Widths* widths,
                                   const cdsim::rtl::BenchOptions* options) {
  return cdsim::rtl::run_bench<Vcd_scan_unit_custom>(*jobs, *widths, *options);
}

// The SystemC kernel and Verilator context this object resolved to: cdsim
// checks that they are its own.
extern "C" void cdsim_rtl_runtime(void** simcontext, void** verilated_context) {
  *simcontext = sc_core::sc_get_curr_simcontext();
  *verilated_context = Verilated::threadContextp();
}
