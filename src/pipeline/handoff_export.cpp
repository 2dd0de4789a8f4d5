#include "src/pipeline/handoff_export.h"

#include <algorithm>

#include "src/pipeline/frame_scene.h"

namespace thaw::pipeline {
std::array<double, 3> rendered_offset(const RunScenario& sc, const meshio::TriangleMesh* outer) {
  std::optional<double> min_y;
  if (outer && !outer->vertices.empty() && sc.shell.rest_on_floor) {
    // As frame_scene: the lowest point of the outer mesh the renderer loaded, whose positions
    // are the file's converted to float (render::from_file_mesh).
    for (const auto& v : outer->vertices) {
      const double y = static_cast<float>(v[1]);
      min_y = min_y ? std::min(*min_y, y) : y;
    }
  }
  return shell_offset(sc, min_y);
}

}  // namespace thaw::pipeline
