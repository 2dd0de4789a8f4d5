#include "src/pipeline/handoff_export.h"

#include <algorithm>
#include <cstdio>

#include "render/geometry/obj_loader.h"
#include "src/common/atomic_file.h"
#include "src/meshio/obj_reader.h"
#include "src/meshio/obj_writer.h"
#include "src/pipeline/frame_scene.h"

namespace thaw::pipeline {
namespace fs = std::filesystem;

std::vector<std::array<double, 3>> rendered_offsets(const RunScenario& sc, const fs::path& mesh_dir,
                                                    const mesh::MeshManifest& meshes) {
  std::vector<std::array<double, 3>> offsets;
  for (const auto& step : meshes.steps) {
    std::optional<double> min_y;
    if (step.outer.file && sc.shell.rest_on_floor) {
      // As frame_scene: the lowest point of the outer mesh the renderer loaded.
      const render::TriangleMesh outer = render::load_obj(mesh_dir / *step.outer.file);
      min_y = outer.positions.front().y;
      for (const auto& p : outer.positions) min_y = std::min<double>(*min_y, p.y);
    }
    offsets.push_back(shell_offset(sc, min_y));
  }
  return offsets;
}

std::string world_obj_name(long step, bool inner) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "shell_%s_%06ld.obj", inner ? "inner" : "outer", step);
  return buf;
}

long write_world_obj_sequence(const fs::path& mesh_dir, const mesh::MeshManifest& meshes,
                              const std::vector<std::array<double, 3>>& offsets,
                              const fs::path& out_dir) {
  ensure_directory(out_dir);
  long files = 0;
  for (std::size_t k = 0; k < meshes.steps.size(); ++k) {
    const mesh::StepRecord& step = meshes.steps[k];
    for (const bool inner : {false, true}) {
      const auto& surface = inner ? step.inner : step.outer;
      meshio::TriangleMesh mesh;
      char comment[160];
      if (surface.file) {
        mesh = meshio::read_obj(mesh_dir / *surface.file);
        for (auto& v : mesh.vertices)
          for (int c = 0; c < 3; ++c) v[c] += offsets[k][c];
        std::snprintf(comment, sizeof comment,
                      "thaw run: step %ld, t = %.17g s, %s surface in world space [m], y up",
                      step.step, step.time_s, inner ? "inner (water|ice)" : "outer (ice|outside)");
      } else {
        std::snprintf(comment, sizeof comment, "thaw run: step %ld, t = %.17g s, no %s surface",
                      step.step, step.time_s, inner ? "inner" : "outer");
      }
      meshio::write_obj(out_dir / world_obj_name(step.step, inner), mesh, comment);
      ++files;
    }
  }
  return files;
}

}  // namespace thaw::pipeline
