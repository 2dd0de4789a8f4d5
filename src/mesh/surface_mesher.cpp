// The only translation unit of thaw that instantiates CGAL Mesh_3 and Polygon_mesh_processing.
// Recipe (found to work on CGAL 5.5, /work/shared/reference/physics.md): an implicit
// Labeled_mesh_domain_3 with relative_error_bound ~1e-6, facet criteria only (the older
// `parameters::facet_angle = ...` style of CGAL 5.5), manifold(), no_perturb(), no_exude(); the
// boundary facets are extracted with facets_in_complex_3_to_triangle_mesh.
#include "src/mesh/surface_mesher.h"

#include "src/mesh/cgal_surface_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/facets_in_complex_3_to_triangle_mesh.h>
#include <CGAL/make_mesh_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace thaw::mesh {

namespace {

using K = cgal::Kernel;
using Point = cgal::Point;
using Domain = CGAL::Labeled_mesh_domain_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using SurfaceMesh = cgal::SurfaceMesh;
using cgal::to_surface_mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

// The implicit function Mesh_3 samples: negative inside.
struct ImplicitShape {
  ShellShape shape;
  K::FT operator()(const Point& p) const { return shape.signed_distance({p.x(), p.y(), p.z()}); }
};

std::string check(const SurfaceMesh& sm) {
  if (sm.number_of_faces() == 0) return "empty mesh";
  if (!CGAL::is_valid_polygon_mesh(sm)) return "not a valid polygon mesh";
  if (!CGAL::is_closed(sm)) return "not closed (has boundary edges)";
  if (!CGAL::is_triangle_mesh(sm)) return "not a triangle mesh";
  std::vector<SurfaceMesh::Halfedge_index> pinched;
  PMP::non_manifold_vertices(sm, std::back_inserter(pinched));
  if (!pinched.empty()) return std::to_string(pinched.size()) + " non-manifold vertices";
  const long euler = static_cast<long>(sm.number_of_vertices()) -
                     static_cast<long>(sm.number_of_edges()) +
                     static_cast<long>(sm.number_of_faces());
  if (euler != 2)
    return "Euler characteristic " + std::to_string(euler) +
           " (expected 2: one sphere-like surface)";
  if (PMP::does_self_intersect(sm)) return "self-intersecting";
  if (!PMP::is_outward_oriented(sm)) return "not outward oriented";
  return "";
}

// The boundary of the meshed solid, facet by facet, each oriented with the inside cell behind it
// (as CGAL's facets_in_complex_3_to_triangle_soup does), vertices numbered in order of first
// appearance. Replaces facets_in_complex_3_to_triangle_mesh, which hashes points and re-checks
// the soup (~15 % of the meshing time at 40k triangles). Returns false if Surface_mesh refuses a
// facet (a non-manifold edge or vertex).
bool boundary_to_surface_mesh(const C3t3& c3t3, SurfaceMesh& sm) {
  const Tr& tr = c3t3.triangulation();
  std::unordered_map<Tr::Vertex_handle, SurfaceMesh::Vertex_index> index;
  index.reserve(c3t3.number_of_facets_in_complex() / 2 + 8);
  sm.reserve(c3t3.number_of_facets_in_complex() / 2 + 8, 3 * c3t3.number_of_facets_in_complex() / 2,
             c3t3.number_of_facets_in_complex());
  for (auto it = c3t3.facets_in_complex_begin(); it != c3t3.facets_in_complex_end(); ++it) {
    const Tr::Cell_handle cell = it->first;
    const int i = it->second;
    std::array<SurfaceMesh::Vertex_index, 3> f;
    for (int k = 0; k < 3; ++k) {
      const Tr::Vertex_handle v = cell->vertex((i + k + 1) & 3);
      auto [pos, added] = index.try_emplace(v);
      if (added) {
        const auto& wp = tr.point(cell, (i + k + 1) & 3);
        pos->second = sm.add_vertex(wp.point());
      }
      f[k] = pos->second;
    }
    // Triangulation_3 orientation convention, same rule as CGAL's soup extraction: swap when
    // (the cell is inside) == (i is odd), so the normal points out of the meshed solid.
    const bool cell_inside = c3t3.is_in_complex(cell);
    if (cell_inside == (i % 2 == 1)) std::swap(f[0], f[1]);
    if (sm.add_face(f[0], f[1], f[2]) == SurfaceMesh::null_face()) return false;
  }
  return true;
}

}  // namespace

std::string check_closed_manifold_outward(const TriangleMesh& mesh) {
  SurfaceMesh sm;
  if (!to_surface_mesh(mesh, sm))
    return "not a 2-manifold oriented polygon mesh (non-manifold edge, bad index or inconsistent "
           "orientation)";
  return check(sm);
}

TriangleMesh mesh_surface(const ShellShape& shape, const MeshOptions& options) {
  return mesh_surface(shape, criteria_for(shape, options), options);
}

struct UncheckedSurface::Cgal {
  SurfaceMesh sm;
};

UncheckedSurface::UncheckedSurface(std::unique_ptr<Cgal> cgal, TriangleMesh mesh)
    : m_cgal(std::move(cgal)), m_mesh(std::move(mesh)) {}
UncheckedSurface::UncheckedSurface(UncheckedSurface&&) noexcept = default;
UncheckedSurface& UncheckedSurface::operator=(UncheckedSurface&&) noexcept = default;
UncheckedSurface::~UncheckedSurface() = default;

std::string UncheckedSurface::check() const {
  return mesh::check(m_cgal->sm);
}

TriangleMesh mesh_surface(const ShellShape& shape, const SurfaceCriteria& c,
                          const MeshOptions& options) {
  UncheckedSurface surface = mesh_surface_unchecked(shape, c, options);
  if (const std::string problem = surface.check(); !problem.empty()) throw MeshError(problem);
  return surface.take_mesh();
}

UncheckedSurface mesh_surface_unchecked(const ShellShape& shape, const SurfaceCriteria& c,
                                        const MeshOptions& options) {
  if (!(shape.radius_m > 0) || !std::isfinite(shape.radius_m) || !(shape.core_half_size_m >= 0))
    throw MeshError("surface radius must be finite and > 0");
  if (!(c.facet_size_m > 0) || !(c.facet_distance_m > 0))
    throw MeshError("facet criteria must be > 0");

  namespace params = CGAL::parameters;
  // The bounding sphere (given by its squared radius) must contain the surface; its centre, the
  // origin, is inside every shape, so the first random ray from it already finds the surface.
  const double bound = 1.2 * shape.bounding_radius();
  CGAL::Random rng(0);  // explicit seed: reproducible whatever ran before on this thread
  // Vertices are placed by bisection to relative_error_bound x (bounding box size). If that
  // error approaches facet_distance the distance criterion can never be met and refinement
  // does not terminate (seen with CGAL's default 1e-3: 12 GB and counting), so keep the
  // placement error at most 1 % of the distance bound.
  const double box = 2 * std::sqrt(3.0) * bound;
  const double error_bound =
      std::min(options.relative_error_bound, 0.01 * c.facet_distance_m / box);
  Domain domain = Domain::create_implicit_mesh_domain(
      ImplicitShape{shape}, K::Sphere_3(CGAL::ORIGIN, bound * bound),
      params::relative_error_bound = error_bound, params::p_rng = &rng);
  Criteria criteria(params::facet_angle = c.facet_angle_deg, params::facet_size = c.facet_size_m,
                    params::facet_distance = c.facet_distance_m);
  C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(), params::no_exude(),
                                      params::manifold());

  auto cgal = std::make_unique<UncheckedSurface::Cgal>();
  SurfaceMesh& sm = cgal->sm;
  if (!boundary_to_surface_mesh(c3t3, sm)) {
    // Not representable facet by facet (only a non-manifold complex does that): let CGAL's
    // general extraction try (it reorients and may duplicate vertices); check() judges the result.
    sm.clear();
    CGAL::facets_in_complex_3_to_triangle_mesh(c3t3, sm);
  }
  if (sm.number_of_faces() > 0 && CGAL::is_closed(sm) && !PMP::is_outward_oriented(sm))
    PMP::reverse_face_orientations(sm);

  TriangleMesh out = cgal::from_surface_mesh(sm);
  if (options.normals) {
    out.normals.reserve(out.vertices.size());
    for (const auto& v : out.vertices) out.normals.push_back(shape.outward_normal(v));
  }
  return UncheckedSurface(std::move(cgal), std::move(out));
}

}  // namespace thaw::mesh
