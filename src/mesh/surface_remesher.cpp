// CGAL Polygon_mesh_processing: isotropic remeshing and the checks of closed surfaces with any
// number of components (the grid surfaces' counterpart of surface_mesher.cpp's checks).
#include "src/mesh/surface_remesher.h"

#include "src/mesh/cgal_surface_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <vector>

namespace thaw::mesh {

namespace {

using cgal::from_surface_mesh;
using cgal::Point;
using cgal::SurfaceMesh;
using cgal::to_surface_mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

std::string check(SurfaceMesh& sm) {
  if (sm.number_of_faces() == 0) return "empty mesh";
  if (!CGAL::is_valid_polygon_mesh(sm)) return "not a valid polygon mesh";
  if (!CGAL::is_closed(sm)) return "not closed (has boundary edges)";
  if (!CGAL::is_triangle_mesh(sm)) return "not a triangle mesh";
  std::vector<SurfaceMesh::Halfedge_index> pinched;
  PMP::non_manifold_vertices(sm, std::back_inserter(pinched));
  if (!pinched.empty()) return std::to_string(pinched.size()) + " non-manifold vertices";
  if (PMP::does_self_intersect(sm)) return "self-intersecting";
  // Orientation per component: the enclosed volume (divergence theorem) of each closed
  // component must be positive.
  auto component = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:thaw_cc", 0).first;
  const std::size_t n = PMP::connected_components(sm, component);
  std::vector<double> six_volume(n, 0.0);
  for (auto f : sm.faces()) {
    std::array<Point, 3> p;
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) p[k++] = sm.point(v);
    six_volume[component[f]] += CGAL::scalar_product(
        p[0] - CGAL::ORIGIN, CGAL::cross_product(p[1] - CGAL::ORIGIN, p[2] - CGAL::ORIGIN));
  }
  for (std::size_t c = 0; c < n; ++c)
    if (!(six_volume[c] > 0))
      return "component " + std::to_string(c) + " of " + std::to_string(n) +
             " not outward oriented";
  return "";
}

}  // namespace

std::string check_closed_oriented_components(const TriangleMesh& mesh) {
  SurfaceMesh sm;
  if (!to_surface_mesh(mesh, sm))
    return "not a 2-manifold oriented polygon mesh (non-manifold edge, bad index or inconsistent "
           "orientation)";
  return check(sm);
}

TriangleMesh remesh_isotropic(const TriangleMesh& mesh, double target_edge_m, int iterations) {
  SurfaceMesh sm;
  if (!to_surface_mesh(mesh, sm)) return {};
  namespace params = CGAL::parameters;
  PMP::isotropic_remeshing(faces(sm), target_edge_m, sm, params::number_of_iterations(iterations));
  sm.collect_garbage();
  return from_surface_mesh(sm);
}

}  // namespace thaw::mesh
