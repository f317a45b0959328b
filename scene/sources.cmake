# The scene front end's sources (docs/scenes.md): scenes, cameras, clipping,
# the hard cases and every loader. Included by scene/CMakeLists.txt (the
# cdsim_scene library) and by tests/fuzz/targets/ (the same list built with
# clang and libFuzzer). Besides the model's headers they need fmt,
# nlohmann_json, libzip, tinyobjloader, tinygltf and stb_image (the last three
# header-only, compiled in third_party.cpp and image_size.cpp).
find_package(PkgConfig REQUIRED)
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET libzip)

set(CDSIM_SCENE_DIR ${CMAKE_CURRENT_LIST_DIR})
set(CDSIM_SCENE_SOURCES
  ${CDSIM_SCENE_DIR}/scene.cpp
  ${CDSIM_SCENE_DIR}/hard_cases.cpp
  ${CDSIM_SCENE_DIR}/loaders/bsp.cpp
  ${CDSIM_SCENE_DIR}/loaders/file_io.cpp
  ${CDSIM_SCENE_DIR}/loaders/gltf.cpp
  ${CDSIM_SCENE_DIR}/loaders/image_size.cpp
  ${CDSIM_SCENE_DIR}/loaders/json_structure.cpp
  ${CDSIM_SCENE_DIR}/loaders/mesh_builder.cpp
  ${CDSIM_SCENE_DIR}/loaders/obj.cpp
  ${CDSIM_SCENE_DIR}/loaders/pk3.cpp
  ${CDSIM_SCENE_DIR}/loaders/scene_file.cpp
  ${CDSIM_SCENE_DIR}/loaders/strict_text.cpp
  ${CDSIM_SCENE_DIR}/loaders/third_party.cpp)
set_source_files_properties(${CDSIM_SCENE_DIR}/loaders/third_party.cpp PROPERTIES COMPILE_OPTIONS "-w")
