#pragma once
// The shell at one step as the GUI shows it: its two surfaces as the renderer takes them (the
// preview) and as the 3D view draws them (src/inspect), with the solver's row for that step.
// Made either by meshing the scenario's initial shell (before any simulation) or by reading a
// simulated, meshed step, on a worker thread. Qt-free (VTK for the 3D view's actors).
#include <vtkActor.h>
#include <vtkSmartPointer.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/geometry/triangle_mesh.h"
#include "sim/format/interface_history.h"
#include "src/inspect/triangle_mesh.h"
#include "src/mesh/triangle_mesh.h"
#include "src/pipeline/run_scenario.h"

namespace thaw::gui {

struct ShellStep {
  sim::InterfaceRecord row;
  /// null when that surface has vanished (or could not be meshed: see `note`)
  std::shared_ptr<const render::TriangleMesh> outer, inner;
  /// the same surfaces for the 3D view (empty when vanished)
  inspect::TriangleMesh outer_view, inner_view;
  /// and drawn as the 3D view draws them (src/inspect/surface_actor.h), their normals computed
  /// when the step is made, off the GUI thread: showing a step then only swaps these actors
  /// (null when the surface has vanished)
  vtkSmartPointer<vtkActor> outer_actor, inner_actor;
  /// why a surface is missing ("" when both are there)
  std::string note;
};

/// The shell geometry the mesher and the frame scene need, from the scenario's [simulation] and
/// [shell] (what summary.json records for them).
sim::ShellGeometry shell_geometry(const sim::Scenario& scenario);

/// The row of t = 0: the scenario's radii and the volumes they enclose.
sim::InterfaceRecord initial_row(const sim::Scenario& scenario);

/// Meshes the initial inner and outer surfaces with the scenario's [mesh] options (src/mesh,
/// CGAL; about 0.1-1 s: call it off the GUI thread). A grid scenario ([shape]) is the run's
/// first frame: its solver's field at t = 0 (sim::simulate at that one time, its row the run's
/// first) meshed by the grid mesher (src/mesh/grid_mesher.h) as `thaw run` meshes it.
ShellStep initial_shell(const pipeline::RunScenario& scenario);

/// A step of a meshed simulation folder: OBJ files (absolute paths, nullopt when vanished).
ShellStep read_shell_step(const sim::InterfaceRecord& row,
                          const std::optional<std::filesystem::path>& outer_obj,
                          const std::optional<std::filesystem::path>& inner_obj);

/// Conversions between the plain mesh types of src/mesh, render/ and src/inspect.
render::TriangleMesh to_render_mesh(const mesh::TriangleMesh& mesh);
inspect::TriangleMesh to_view_mesh(const render::TriangleMesh& mesh);

}  // namespace thaw::gui
