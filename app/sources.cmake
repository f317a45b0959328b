# The command line and the commands, all but main (app/cdsim.cpp). Included by
# the top CMakeLists.txt (cdsim_app) and by tests/fuzz/targets/ (fuzz_cli and
# fuzz_sweep_file link them too).
set(CDSIM_APP_DIR ${CMAKE_CURRENT_LIST_DIR})
set(CDSIM_APP_SOURCES
  ${CDSIM_APP_DIR}/cli.cpp
  ${CDSIM_APP_DIR}/cli_checks.cpp
  ${CDSIM_APP_DIR}/common.cpp
  ${CDSIM_APP_DIR}/sweep.cpp
  ${CDSIM_APP_DIR}/sweep_file.cpp
  ${CDSIM_APP_DIR}/render.cpp
  ${CDSIM_APP_DIR}/size.cpp
  ${CDSIM_APP_DIR}/area.cpp
  ${CDSIM_APP_DIR}/regress_cli.cpp
  ${CDSIM_APP_DIR}/choose.cpp
  ${CDSIM_APP_DIR}/area_model.cpp
  ${CDSIM_APP_DIR}/flagged_triangles.cpp
  ${CDSIM_APP_DIR}/sta.cpp
  ${CDSIM_APP_DIR}/netlist_writer.cpp
  ${CDSIM_APP_DIR}/area_recovery.cpp)
set_source_files_properties(${CDSIM_APP_DIR}/render.cpp PROPERTIES
  COMPILE_OPTIONS "-Wno-conversion;-Wno-missing-field-initializers")
