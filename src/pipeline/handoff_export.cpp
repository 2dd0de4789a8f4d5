#include "src/pipeline/handoff_export.h"

#include <algorithm>
#include <cstdio>

#include "base/atomic_file.h"
#include "base/obj_writer.h"
#include "src/pipeline/frame_scene.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

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

std::string world_obj_name(long step, bool inner) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "shell_%s_%06ld.obj", inner ? "inner" : "outer", step);
  return buf;
}

void write_world_obj(const fs::path& out_dir, long step, double time_s, bool inner,
                     const meshio::TriangleMesh* placed) {
  char comment[160];
  if (placed)
    std::snprintf(comment, sizeof comment,
                  "thaw run: step %ld, t = %.17g s, %s surface in world space [m], y up", step,
                  time_s, inner ? "inner (water|ice)" : "outer (ice|outside)");
  else
    std::snprintf(comment, sizeof comment, "thaw run: step %ld, t = %.17g s, no %s surface", step,
                  time_s, inner ? "inner" : "outer");
  meshio::write_obj(out_dir / world_obj_name(step, inner),
                    placed ? *placed : meshio::TriangleMesh{}, comment);
}

}  // namespace thaw::pipeline
