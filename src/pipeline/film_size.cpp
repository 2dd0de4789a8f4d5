#include "src/pipeline/film_size.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "base/error.h"
#include "base/format/toml_table.h"
#include "base/number_text.h"
#include "sim/format/interface_history.h"
#include "src/mesh/mesh_options.h"
#include "src/mesh/shell_shape.h"

namespace thaw::pipeline {
namespace {

/// "3 m": the key's value in the unit of its name, and what it would be in centimetres or
/// millimetres, had the user meant them.
std::string metres_hint(double value_m) {
  return "the keys are in metres: " + shortest_text(value_m) + " cm is " +
         shortest_text(value_m / 100) + ", " + shortest_text(value_m) + " mm is " +
         shortest_text(value_m / 1000);
}

[[noreturn]] void too_large(const TomlTable& root, const char* section, const std::string& key,
                            double value_m, double across_m) {
  char across[64];
  std::snprintf(across, sizeof across, "%.3g m", across_m);
  const std::string problem = shortest_text(value_m) + " m makes a piece " + across +
                              " across; thaw run films pieces up to " +
                              shortest_text(kMaxFilmExtentM) + " m across (" +
                              metres_hint(value_m) + ")";
  if (const auto t = root.optional_table(section)) t->fail(key, problem);
  root.fail(std::string(section) + "." + key, problem);
}

/// The largest extent of one [shape] body [m] (an OBJ's is known once it is read: the grid's
/// cell count rule bounds it).
double shape_extent(const sim::ShapeSpec& s) {
  switch (s.kind) {
    case sim::ShapeKind::box:
      return *std::max_element(s.size_m.begin(), s.size_m.end());
    case sim::ShapeKind::sphere:
      return 2 * s.radius_m;
    case sim::ShapeKind::cylinder:
      return std::max(2 * s.radius_m, s.height_m);
    case sim::ShapeKind::obj:
      return 0;
  }
  return 0;
}

void check_shell(const TomlTable& root, const RunScenario& r) {
  const sim::Scenario& s = r.simulation;
  sim::ShellGeometry g;
  g.geometry = s.geometry;
  g.length_m = s.length_m;
  g.lateral_size_m = s.lateral_size_m;
  g.planar_symmetric = s.inner_kind == sim::InnerBoundary::symmetry;
  const mesh::ShellShape shape = mesh::ShellShape::from_geometry(g, s.outer_radius_m);
  const double across = 2 * shape.bounding_radius();
  if (across > kMaxFilmExtentM) {
    // Name the key that makes it large.
    const char* key = "outer_radius_m";
    double value = s.outer_radius_m;
    if (s.geometry == sim::Geometry::cylinder && s.length_m > 2 * s.outer_radius_m)
      key = "length_m", value = s.length_m;
    if (s.geometry == sim::Geometry::planar && s.lateral_size_m > s.outer_radius_m)
      key = "lateral_size_m", value = s.lateral_size_m;
    too_large(root, "shell", key, value, across);
  }
  // The largest surface is the outer one at t = 0 (the solver never grows it): the mesher's own
  // estimate, before any work, so that the mesh stage does not fail after the simulation.
  const mesh::MeshOptions options = mesh::resolve_triangle_target(
      mesh::resolve_scene(r.mesh, shape.bounding_radius()), shape.area());
  const double triangles = mesh::estimate_triangles(shape, mesh::criteria_for(shape, options));
  if (!(triangles > mesh::kMaxTrianglesPerSurface)) return;
  char count[32];
  std::snprintf(count, sizeof count, "%.2g", triangles);
  const std::string problem = std::string("gives about ") + count +
                              " triangles on the outer surface (" + shortest_text(across) +
                              " m across), more than the 5e7 a surface may have; use a longer "
                              "edge_length_m or a triangle target ([mesh] triangles)";
  if (const auto t = root.optional_table("mesh")) t->fail("edge_length_m", problem);
  root.fail("mesh.edge_length_m", problem);
}

}  // namespace

void check_film_size(const TomlTable& root, const RunScenario& r) {
  const sim::Scenario& s = r.simulation;
  if (s.grid == sim::GridGeometry::none) return check_shell(root, r);
  for (const auto& [key, spec] :
       {std::pair<const char*, const sim::ShapeSpec*>{"outer", &s.shape.outer},
        {"cavity", s.shape.cavity ? &*s.shape.cavity : nullptr}}) {
    if (!spec) continue;
    const double across = shape_extent(*spec);
    if (across > kMaxFilmExtentM) {
      const double value = spec->kind == sim::ShapeKind::box      ? across
                           : spec->kind == sim::ShapeKind::sphere ? spec->radius_m
                                                                  : across;
      too_large(root, "shape", key, value, across);
    }
  }
}

}  // namespace thaw::pipeline
