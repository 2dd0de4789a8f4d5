#include "src/inspect/vtk_polydata.h"

#include <vtkCellArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>

namespace thaw::inspect {

vtkSmartPointer<vtkPolyData> to_polydata(const TriangleMesh& mesh) {
  return to_polydata(mesh.vertices, mesh.triangles);
}

vtkSmartPointer<vtkPolyData> to_polydata(
    const std::vector<std::array<double, 3>>& vertices,
    const std::vector<std::array<std::int64_t, 3>>& triangles) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i)
    points->SetPoint(static_cast<vtkIdType>(i), vertices[i].data());
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(static_cast<vtkIdType>(triangles.size()),
                       static_cast<vtkIdType>(3 * triangles.size()));
  for (const auto& t : triangles) {
    const vtkIdType ids[3] = {static_cast<vtkIdType>(t[0]), static_cast<vtkIdType>(t[1]),
                              static_cast<vtkIdType>(t[2])};
    polys->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  return poly;
}

}  // namespace thaw::inspect
