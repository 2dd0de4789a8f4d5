#include "src/inspect/surface_actor.h"

#include <vtkNew.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>

#include "src/inspect/vtk_polydata.h"

namespace thaw::inspect {
namespace {

struct Look {
  double color[3];
  double edge[3];
  double opacity;
};

Look look_of(SurfaceRole role) {
  switch (role) {
    case SurfaceRole::inner:
      return {{0.16, 0.42, 0.80}, {0.06, 0.18, 0.40}, 1.0};
    case SurfaceRole::outer:
      return {{0.80, 0.92, 1.00}, {0.45, 0.62, 0.78}, 0.28};
    case SurfaceRole::single:
      break;
  }
  return {{0.82, 0.84, 0.86}, {0.20, 0.22, 0.26}, 1.0};
}

}  // namespace

vtkSmartPointer<vtkActor> surface_actor(const TriangleMesh& mesh, SurfaceRole role, bool edges) {
  vtkNew<vtkPolyDataNormals> normals;  // smooth shading; the edges show the facets
  normals->SetInputData(to_polydata(mesh));
  normals->SplittingOff();
  normals->ConsistencyOff();
  normals->AutoOrientNormalsOff();
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(normals->GetOutputPort());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  const Look look = look_of(role);
  vtkProperty* prop = actor->GetProperty();
  prop->SetColor(look.color[0], look.color[1], look.color[2]);
  prop->SetOpacity(look.opacity);
  prop->SetSpecular(role == SurfaceRole::outer ? 0.6 : 0.3);
  prop->SetSpecularPower(40);
  if (edges) {
    prop->EdgeVisibilityOn();
    prop->SetEdgeColor(look.edge[0], look.edge[1], look.edge[2]);
    prop->SetLineWidth(1.0);
  }
  if (role == SurfaceRole::outer) prop->BackfaceCullingOff();
  return actor;
}

}  // namespace thaw::inspect
