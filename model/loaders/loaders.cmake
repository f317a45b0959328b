# Scene and mesh loaders (docs/scenes.md), added to cdsim_model. Included from
# the top-level CMakeLists.txt after cdsim_model is defined; tests/fuzz/ builds
# the same list with clang and libFuzzer.
find_package(PkgConfig REQUIRED)
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)

set(CDSIM_LOADERS_DIR ${CMAKE_CURRENT_LIST_DIR})
set(CDSIM_LOADER_SOURCES
  ${CDSIM_LOADERS_DIR}/bsp.cpp
  ${CDSIM_LOADERS_DIR}/file_io.cpp
  ${CDSIM_LOADERS_DIR}/gltf.cpp
  ${CDSIM_LOADERS_DIR}/image_size.cpp
  ${CDSIM_LOADERS_DIR}/mesh_builder.cpp
  ${CDSIM_LOADERS_DIR}/obj.cpp
  ${CDSIM_LOADERS_DIR}/pk3.cpp
  ${CDSIM_LOADERS_DIR}/scene_file.cpp
  ${CDSIM_LOADERS_DIR}/third_party.cpp)
set_source_files_properties(${CDSIM_LOADERS_DIR}/third_party.cpp PROPERTIES COMPILE_OPTIONS "-w")

if(TARGET cdsim_model)
  target_sources(cdsim_model PRIVATE ${CDSIM_LOADER_SOURCES})
  target_link_libraries(cdsim_model PUBLIC PkgConfig::LIBZIP)
endif()
