# cdsim's infrastructure, apart from the model (issue 38): caches and atomic
# output files, the tools' child processes, SIGINT/SIGTERM, progress lines,
# shards, and the reports that name scene, widths, seed and build. Included by
# the top CMakeLists.txt and by tests/fuzz/targets/ (the same lists with
# clang and libFuzzer).
set(CDSIM_SUPPORT_DIR ${CMAKE_CURRENT_LIST_DIR})
# No dependency on the model: the model links it (evaluate stops on SIGINT).
set(CDSIM_SUPPORT_SOURCES
  ${CDSIM_SUPPORT_DIR}/cache_files.cpp
  ${CDSIM_SUPPORT_DIR}/child_process.cpp
  ${CDSIM_SUPPORT_DIR}/interrupt.cpp
  ${CDSIM_SUPPORT_DIR}/progress.cpp)
# Reports of the model's results: on top of the model.
set(CDSIM_REPORT_SOURCES ${CDSIM_SUPPORT_DIR}/report.cpp)
