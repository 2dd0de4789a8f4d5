#include "src/mesh/grid_mesher.h"

#include <vector>

#include "src/mesh/grid_surface.h"
#include "src/mesh/node_lattice.h"
#include "src/mesh/surface_mesher.h"
#include "src/mesh/surface_remesher.h"
#include "src/mesh/taubin_smoothing.h"

namespace thaw::mesh {

namespace {
// The surface handed out: remeshed and smoothed if that passes the checks, else the
// marching-tetrahedra surface smoothed, else as extracted (closed, manifold and free of
// self-intersections by construction; still checked).
void finish(TriangleMesh& m, const NodeLattice& ice, const GridMeshOptions& o, double edge,
            bool inner, std::string& note) {
  if (m.faces.empty()) return;
  const char* which = inner ? "inner" : "outer";
  auto smoothed = [&](TriangleMesh c) {
    if (o.taubin_passes > 0) {
      TaubinOptions t;
      t.passes = o.taubin_passes;
      taubin_smooth(c, t);
    }
    return c;
  };
  std::vector<TriangleMesh> candidates;
  if (o.remesh_iterations > 0)
    candidates.push_back(smoothed(remesh_isotropic(m, edge, o.remesh_iterations)));
  candidates.push_back(smoothed(m));
  candidates.push_back(m);
  std::string problem;
  for (TriangleMesh& c : candidates) {
    problem = check_closed_oriented_components(c);
    if (problem.empty()) {
      m = std::move(c);
      if (o.normals) set_lattice_normals(m, ice, inner);
      return;
    }
    if (note.empty()) note = std::string(which) + ": " + problem;
  }
  throw MeshError(std::string(which) + " grid surface: " + problem);
}
}  // namespace

GridMeshResult mesh_grid_field(const sim::GridField& field, const GridMeshOptions& o) {
  const NodeLattice ice = NodeLattice::from_ice_fraction(field, o.smoothing_passes);
  const NodeLattice water = NodeLattice::from_water_fraction(field);
  GridSurfaces s = extract_grid_surfaces(ice, water);
  GridMeshResult r;
  r.cavities = s.cavities;
  r.cavity_water_fraction = s.cavity_water_fraction;
  const double edge = o.edge_length_m > 0 ? o.edge_length_m : field.spacing_m;
  finish(s.outer, ice, o, edge, false, r.remesh_problem);
  finish(s.inner, ice, o, edge, true, r.remesh_problem);
  r.outer = std::move(s.outer);
  r.inner = std::move(s.inner);
  return r;
}

}  // namespace thaw::mesh
