#pragma once
// How a surface is drawn in VTK, written once for the pictures of `thaw inspect --screenshot`
// (screenshot.cpp) and the 3D view of `thaw gui` (src/gui/shell_view.cpp): a lone mesh opaque
// grey, an inner surface (water|ice) opaque water blue, an outer surface (ice|air) translucent
// ice, smooth shaded with optional triangle edges. This header includes VTK: only src/inspect and
// src/gui may include it.
#include <vtkActor.h>
#include <vtkSmartPointer.h>

#include "src/inspect/surface_role.h"
#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect {

/// An actor drawing `mesh` in the look of `role` (with its triangle edges if `edges`).
vtkSmartPointer<vtkActor> surface_actor(const TriangleMesh& mesh, SurfaceRole role, bool edges);

}  // namespace thaw::inspect
