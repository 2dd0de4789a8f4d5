#pragma once
// Conversion of thaw's plain triangle mesh to VTK's vtkPolyData (double-precision points, one
// triangle cell per face, order kept). Internal to src/inspect: the only folder that sees VTK.
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect {

/// A vtkPolyData with all vertices and the triangles of `mesh` (indices must be in range).
vtkSmartPointer<vtkPolyData> to_polydata(const TriangleMesh& mesh);

}  // namespace thaw::inspect
