# Writes generated/build_info.hpp at every build (not only at configure time),
# so that every figure the tool prints names the commit it was built from,
# "-dirty" included; the file is rewritten only when its content changes.
# Run by the cdsim_build_info target (CMakeLists.txt) with -D: SOURCE_DIR,
# INPUT, OUTPUT, CMAKE_CXX_COMPILER_ID, CMAKE_CXX_COMPILER_VERSION,
# CMAKE_BUILD_TYPE, PROJECT_SOURCE_DIR.
execute_process(COMMAND git describe --always --dirty
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE CDSIM_REVISION OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT CDSIM_REVISION)
  set(CDSIM_REVISION "unknown")
endif()
configure_file(${INPUT} ${OUTPUT}.new @ONLY)
file(COPY_FILE ${OUTPUT}.new ${OUTPUT} ONLY_IF_DIFFERENT)
file(REMOVE ${OUTPUT}.new)
