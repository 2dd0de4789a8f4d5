#include "src/gui/shell_step.h"

#include <vtkAlgorithm.h>
#include <vtkMapper.h>

#include "base/check.h"
#include "base/error.h"
#include "render/geometry/obj_loader.h"
#include "sim/simulate.h"
#include "src/inspect/surface_actor.h"
#include "src/mesh/grid_series.h"
#include "src/mesh/shell_shape.h"
#include "src/mesh/surface_mesher.h"
#include "src/pipeline/water_budget.h"

namespace thaw::gui {

sim::ShellGeometry shell_geometry(const sim::Scenario& s) {
  sim::ShellGeometry g;
  g.geometry = s.geometry;
  g.length_m = s.length_m;
  g.lateral_size_m = s.lateral_size_m;
  g.planar_symmetric = s.inner_kind == sim::InnerBoundary::symmetry;
  return g;
}

sim::InterfaceRecord initial_row(const sim::Scenario& s) {
  sim::InterfaceRecord row;
  row.inner_radius_m = s.inner_radius_m;
  row.outer_radius_m = s.outer_radius_m;
  const sim::ShellGeometry g = shell_geometry(s);
  row.liquid_volume_m3 = pipeline::shell_surface_volume_m3(g, s.inner_radius_m);
  row.ice_volume_m3 = pipeline::shell_surface_volume_m3(g, s.outer_radius_m) - row.liquid_volume_m3;
  return row;
}

render::TriangleMesh to_render_mesh(const mesh::TriangleMesh& m) {
  // Through the file type: the one conversion of each side (mesh and render triangle_mesh.h).
  return render::from_file_mesh(mesh::to_file_mesh(m), "the mesher's surface");
}

inspect::TriangleMesh to_view_mesh(const render::TriangleMesh& m) {
  inspect::TriangleMesh v;
  v.vertices.reserve(m.positions.size());
  for (const auto& p : m.positions) v.vertices.push_back({p.x, p.y, p.z});
  v.triangles.reserve(m.triangles.size());
  for (const auto& t : m.triangles) v.triangles.push_back({t[0], t[1], t[2]});
  return v;
}

namespace {

void set_surface(ShellStep& step, bool outer, render::TriangleMesh mesh) {
  auto shared = std::make_shared<const render::TriangleMesh>(std::move(mesh));
  inspect::TriangleMesh& view = outer ? step.outer_view : step.inner_view;
  view = to_view_mesh(*shared);
  (outer ? step.outer : step.inner) = std::move(shared);
  // The actor with its smooth normals computed now (the mapper's input filter brought up to
  // date): the GUI thread's draw then only uploads the triangles.
  vtkSmartPointer<vtkActor> actor = inspect::surface_actor(
      view, outer ? inspect::SurfaceRole::outer : inspect::SurfaceRole::inner, /*edges=*/outer);
  if (vtkAlgorithm* input = actor->GetMapper()->GetInputAlgorithm()) input->Update();
  (outer ? step.outer_actor : step.inner_actor) = std::move(actor);
}

// A grid scenario's first frame as `thaw run` makes it: the solver's output at t = 0 (the
// [shape] sampled into cell fractions by sim/grid/grid_builder.h, the same call and row as the
// run's first interfaces.csv line), meshed by the grid mesher with the run's [mesh] options.
ShellStep initial_grid_shell(const pipeline::RunScenario& sc) {
  ShellStep step;
  const sim::SimulationResult first = sim::simulate(sc.simulation, std::vector<double>{0.0});
  THAW_CHECK(first.fields.size() == 1, "a grid run sampled at t = 0 keeps that one field");
  step.row = first.interface_records().front();
  try {
    const mesh::GridMeshResult m =
        mesh::mesh_grid_field(first.fields.front(), mesh::grid_mesh_options(sc.mesh));
    if (!m.outer.faces.empty()) set_surface(step, true, to_render_mesh(m.outer));
    if (!m.inner.faces.empty() && step.outer) set_surface(step, false, to_render_mesh(m.inner));
  } catch (const mesh::MeshError& e) {
    step.note = std::string("the initial body could not be meshed: ") + e.what();
  }
  return step;
}

}  // namespace

ShellStep initial_shell(const pipeline::RunScenario& sc) {
  ShellStep step;
  if (sc.simulation.grid != sim::GridGeometry::none) return initial_grid_shell(sc);
  step.row = initial_row(sc.simulation);
  const sim::ShellGeometry g = shell_geometry(sc.simulation);
  const auto outer_shape = mesh::ShellShape::from_geometry(g, sc.simulation.outer_radius_m);
  const mesh::MeshOptions options = mesh::resolve_triangle_target(
      mesh::resolve_scene(sc.mesh, outer_shape.bounding_radius()), outer_shape.area());
  try {
    if (sc.simulation.outer_radius_m > sc.simulation.inner_radius_m)
      set_surface(step, true, to_render_mesh(mesh::mesh_surface(outer_shape, options)));
    const auto inner_shape = mesh::ShellShape::from_geometry(g, sc.simulation.inner_radius_m);
    if (sc.simulation.inner_radius_m > options.min_radius_m && step.outer)
      set_surface(step, false, to_render_mesh(mesh::mesh_surface(inner_shape, options)));
  } catch (const mesh::MeshError& e) {
    step.note = std::string("the initial shell could not be meshed: ") + e.what();
  }
  return step;
}

ShellStep read_shell_step(const sim::InterfaceRecord& row,
                          const std::optional<std::filesystem::path>& outer_obj,
                          const std::optional<std::filesystem::path>& inner_obj) {
  ShellStep step;
  step.row = row;
  if (outer_obj) set_surface(step, true, render::load_obj(*outer_obj));
  if (inner_obj) set_surface(step, false, render::load_obj(*inner_obj));
  return step;
}

}  // namespace thaw::gui
