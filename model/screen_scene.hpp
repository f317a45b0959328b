// What the model draws: a list of screen-space triangles and the viewport they
// lie in. The scene front end (scene/: files, cameras, clipping) produces it;
// the model (evaluate.hpp, report.hpp) consumes it and needs nothing else of
// the front end.
#pragma once

#include <string>
#include <vector>

#include "triangle.hpp"

namespace cdsim {

struct Scene {
  std::string name;
  std::string description;  // how to make it again: camera, source
  int width = 0, height = 0;
  std::vector<ScreenTriangle> triangles;
};

}  // namespace cdsim
