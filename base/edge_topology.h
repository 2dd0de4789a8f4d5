#pragma once
// Edge topology of a triangle soup in linear time: every undirected edge is found through a hash
// table keyed by its two vertex indices (no sorting, no per-vertex search such as
// vtkFeatureEdges', which is quadratic in the number of triangles around an edge and asks for
// N^2/200 entries on large meshes). Counts edges used once (boundary) and three or more times
// (non-manifold), manifold edges whose two triangles traverse them the same way (inconsistent
// orientation), and edge-connected components (union-find). Knows nothing about files.
#include <array>
#include <cstdint>
#include <vector>

namespace thaw::meshio {

struct EdgeTopology {
  std::int64_t edges = 0;               ///< distinct undirected edges (by vertex index)
  std::int64_t boundary_edges = 0;      ///< used by exactly one triangle
  std::int64_t non_manifold_edges = 0;  ///< used by three or more triangles
  std::int64_t inconsistent_edges = 0;  ///< used twice in the same direction
  std::int64_t used_vertices = 0;       ///< vertices some triangle refers to
  std::int64_t components = 0;          ///< edge-connected pieces over the used vertices
  double min_edge_m = 0, mean_edge_m = 0, max_edge_m = 0;  ///< edge lengths [m]
};

/// Topology of `triangles` (0-based indices into `vertices`, each < vertices.size(), three
/// distinct corners: degenerate triangles must be left out by the caller). O(V + F) time and
/// memory.
EdgeTopology edge_topology(const std::vector<std::array<double, 3>>& vertices,
                           const std::vector<std::array<std::int64_t, 3>>& triangles);

}  // namespace thaw::meshio
