#pragma once
// Conversion of thaw's plain triangle mesh to VTK's vtkPolyData (double-precision points, one
// triangle cell per face, order kept). Internal to src/inspect: the only folder that sees VTK.
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect {

/// A vtkPolyData with all vertices and the triangles of `mesh` (indices must be in range).
vtkSmartPointer<vtkPolyData> to_polydata(const TriangleMesh& mesh);

/// The same from the parts: `vertices` [m], `triangles` 0-based (a subset of a mesh's faces).
vtkSmartPointer<vtkPolyData> to_polydata(const std::vector<std::array<double, 3>>& vertices,
                                         const std::vector<std::array<std::int64_t, 3>>& triangles);

}  // namespace thaw::inspect
