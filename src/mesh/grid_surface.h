#pragma once
// The surfaces of the ice body in a GridField: an isosurface (ice = 1/2 by default) of its node
// lattice (node_lattice.h), extracted by marching tetrahedra on the Kuhn decomposition of every
// lattice cube (six tetrahedra around the cube's main diagonal, conforming between cubes), so the
// surface is closed, 2-manifold and free of self-intersections by construction, with one vertex per
// crossed lattice edge. Each piece is classified by the non-ice region on its far side: regions
// are the non-ice nodes connected along tetrahedron edges; the region holding the lattice's air
// border is the outside, every other one is a sealed cavity.
//   outer: ice | outside, oriented out of the ice;
//   inner: cavity | ice around every sealed cavity, oriented out of the cavity (into the ice),
//          the convention of the 1D inner surface (a closed surface around the water).
// After break-through the cavity joins the outside and only `outer` is left. Knows nothing about
// CGAL or files.
#include "sim/format/grid_field_file.h"
#include "src/mesh/node_lattice.h"
#include "src/mesh/triangle_mesh.h"

namespace thaw::mesh {

struct GridSurfaces {
  TriangleMesh outer, inner;
  /// Sealed cavities (connected non-ice regions not joined to the outside).
  int cavities = 0;
  /// Mean water fraction of the cavities' nodes (0 without cavities): ~1 for a water-filled core.
  double cavity_water_fraction = 0;
};

/// Marching tetrahedra on the isosurface ice = `iso` of `ice` (values in [0, 1]; ice where the
/// value exceeds `iso`); `water` (same lattice) gives the cavities' water content. Vertices where
/// the isosurface crosses a lattice edge are kept at least 1e-3 of the edge from its nodes, so no
/// triangle degenerates to a point. No normals.
GridSurfaces extract_grid_surfaces(const NodeLattice& ice, const NodeLattice& water,
                                   float iso = 0.5f);

}  // namespace thaw::mesh
