# The two tops and the RTL files each reads, named once: sim/CMakeLists.txt verilates them,
# and cdsim area (app/area.cpp) synthesises and hashes them through the header
# cdsim_write_rtl_sources_header() writes.
set(CDSIM_RTL_TOP cd_scan_unit)
set(CDSIM_RTL_ADAPTIVE_TOP adaptive_unit)
set(CDSIM_RTL_FILES
  cd_scan_unit.sv setup_engine.sv setup_stage_a.sv setup_stage_b.sv setup_stage_c.sv setup_dividers.sv
  setup_stage_d.sv setup_fill.sv setup_multipliers.sv reciprocal.sv reciprocal_operand.sv plane_accumulator.sv
  affine_setup.sv affine_sub_datapath.sv quad_sub_datapath.sv exact_points.sv kim_datapath.sv
  pixel_divide.sv serial_divider.sv shift_round.sv scanline_table.sv column_walker.sv
  context_register.sv correction_adder.sv)
# The adaptive unit's own files; it reads the scan unit's too.
set(CDSIM_RTL_ADAPTIVE_FILES adaptive_unit.sv adaptive_split.sv)

function(cdsim_write_rtl_sources_header output)
  string(JOIN "\", \"" scan ${CDSIM_RTL_FILES})
  string(JOIN "\", \"" adaptive ${CDSIM_RTL_ADAPTIVE_FILES})
  file(CONFIGURE OUTPUT ${output} CONTENT
"// Generated from cmake/rtl_sources.cmake: the RTL files (in rtl/) each top reads.
#pragma once
namespace cdsim {
inline constexpr const char* kScanUnitTop = \"${CDSIM_RTL_TOP}\";
inline constexpr const char* kAdaptiveUnitTop = \"${CDSIM_RTL_ADAPTIVE_TOP}\";
inline constexpr const char* kScanUnitRtlFiles[] = {\"${scan}\"};
// The adaptive unit's own files; it reads kScanUnitRtlFiles too.
inline constexpr const char* kAdaptiveRtlFiles[] = {\"${adaptive}\"};
}  // namespace cdsim
" @ONLY)
endfunction()
