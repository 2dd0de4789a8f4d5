#pragma once
// thaw's TriangleMesh and CGAL's Surface_mesh, for src/mesh's two CGAL translation units
// (surface_mesher.cpp, surface_remesher.cpp): the one conversion each way. Includes CGAL: only
// those .cpp files include it (no header other units see may).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/iterator.h>

#include <array>
#include <cstddef>
#include <vector>

#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

/// Builds `sm` from `mesh`; false if the soup is not a polygon mesh (a bad index, a non-manifold
/// edge or an inconsistent orientation cannot be represented).
inline bool to_surface_mesh(const TriangleMesh& mesh, SurfaceMesh& sm) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::vector<Point> points;
  points.reserve(mesh.vertices.size());
  for (const auto& v : mesh.vertices) points.emplace_back(v[0], v[1], v[2]);
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(mesh.faces.size());
  for (const auto& f : mesh.faces) {
    for (int i : f)
      if (i < 0 || static_cast<std::size_t>(i) >= points.size()) return false;
    faces.push_back({static_cast<std::size_t>(f[0]), static_cast<std::size_t>(f[1]),
                     static_cast<std::size_t>(f[2])});
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(faces)) return false;
  PMP::polygon_soup_to_polygon_mesh(points, faces, sm);
  return true;
}

/// The vertices of `sm` in its order (removed ones skipped) and its faces by them; no normals.
inline TriangleMesh from_surface_mesh(const SurfaceMesh& sm) {
  TriangleMesh out;
  out.vertices.reserve(sm.number_of_vertices());
  std::vector<int> index(sm.num_vertices(), -1);
  for (auto v : sm.vertices()) {
    const Point& p = sm.point(v);
    index[v.idx()] = static_cast<int>(out.vertices.size());
    out.vertices.push_back({p.x(), p.y(), p.z()});
  }
  out.faces.reserve(sm.number_of_faces());
  for (auto f : sm.faces()) {
    std::array<int, 3> tri{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) tri[k++] = index[v.idx()];
    out.faces.push_back(tri);
  }
  return out;
}

}  // namespace thaw::mesh::cgal
