# The bit-accurate model of the unit (docs/microarchitecture.md). Included by
# the top CMakeLists.txt and by tests/fuzz/targets/.
set(CDSIM_MODEL_DIR ${CMAKE_CURRENT_LIST_DIR})
set(CDSIM_MODEL_SOURCES
  ${CDSIM_MODEL_DIR}/fixed.cpp
  ${CDSIM_MODEL_DIR}/widths.cpp
  ${CDSIM_MODEL_DIR}/derived_widths.cpp
  ${CDSIM_MODEL_DIR}/setup_schedule.cpp
  ${CDSIM_MODEL_DIR}/triangle.cpp
  ${CDSIM_MODEL_DIR}/pixel_coverage.cpp
  ${CDSIM_MODEL_DIR}/exact.cpp
  ${CDSIM_MODEL_DIR}/encodings.cpp
  ${CDSIM_MODEL_DIR}/design.cpp
  ${CDSIM_MODEL_DIR}/line_geometry.cpp
  ${CDSIM_MODEL_DIR}/setup_engine.cpp
  ${CDSIM_MODEL_DIR}/column_walker.cpp
  ${CDSIM_MODEL_DIR}/divide_datapath.cpp
  ${CDSIM_MODEL_DIR}/kim_datapath.cpp
  ${CDSIM_MODEL_DIR}/adaptive_split.cpp
  ${CDSIM_MODEL_DIR}/affine_datapath.cpp
  ${CDSIM_MODEL_DIR}/scan_unit.cpp
  ${CDSIM_MODEL_DIR}/timing.cpp
  ${CDSIM_MODEL_DIR}/evaluate.cpp)
