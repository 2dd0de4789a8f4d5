// Tests of base/edge_topology: counts on meshes whose topology is known by construction
// (icosphere: V - E + F = 2, every edge shared by two triangles in opposite directions), and the
// issue-12 input that took vtkFeatureEdges over 120 s.
#include "base/edge_topology.h"

#include <gtest/gtest.h>

#include "tests/src/inspect/icosphere.h"

namespace thaw::meshio {
namespace {

TEST(EdgeTopology, ClosedIcosphere) {
  const TriangleMesh m = inspect::testing::icosphere(1.0, 3);  // 1280 triangles
  const EdgeTopology t = edge_topology(m.vertices, m.triangles);
  // Closed triangle surface: each triangle has 3 edges, each edge 2 triangles -> E = 3F/2.
  EXPECT_EQ(t.edges, 3 * static_cast<std::int64_t>(m.triangles.size()) / 2);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.non_manifold_edges, 0);
  EXPECT_EQ(t.inconsistent_edges, 0);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.used_vertices - t.edges + static_cast<std::int64_t>(m.triangles.size()), 2);
  EXPECT_GT(t.min_edge_m, 0);
  EXPECT_LE(t.min_edge_m, t.mean_edge_m);
  EXPECT_LE(t.mean_edge_m, t.max_edge_m);
}

TEST(EdgeTopology, HoleFlipAndSecondComponent) {
  TriangleMesh m = inspect::testing::icosphere(1.0, 1);  // 80 triangles
  const std::int64_t n = static_cast<std::int64_t>(m.vertices.size());
  // Flip one triangle: its 3 edges are each traversed twice in the same direction.
  std::swap(m.triangles[5][1], m.triangles[5][2]);
  EdgeTopology t = edge_topology(m.vertices, m.triangles);
  EXPECT_EQ(t.inconsistent_edges, 3);
  EXPECT_EQ(t.boundary_edges, 0);
  // Remove another triangle (not touching the flipped one) -> its 3 edges become boundary.
  m.triangles.erase(m.triangles.begin() + 40);
  // A separate triangle on three new vertices: a second component with 3 boundary edges.
  m.vertices.push_back({5, 0, 0});
  m.vertices.push_back({6, 0, 0});
  m.vertices.push_back({5, 1, 0});
  m.triangles.push_back({n, n + 1, n + 2});
  t = edge_topology(m.vertices, m.triangles);
  EXPECT_EQ(t.boundary_edges, 6);
  EXPECT_EQ(t.components, 2);
  EXPECT_DOUBLE_EQ(t.max_edge_m, std::sqrt(2.0));  // the separate triangle's hypotenuse
}

TEST(EdgeTopology, ManyCopiesOfOneTriangleIsOneNonManifoldEdgeTriple) {
  // Issue 12: 3 vertices and 4000 copies of "f 1 2 3" (vtkFeatureEdges: > 120 s).
  const std::vector<std::array<double, 3>> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::array<std::int64_t, 3>> f(4000, {0, 1, 2});
  const EdgeTopology t = edge_topology(v, f);
  EXPECT_EQ(t.edges, 3);
  EXPECT_EQ(t.non_manifold_edges, 3);
  EXPECT_EQ(t.boundary_edges, 0);
  EXPECT_EQ(t.components, 1);
}

TEST(EdgeTopology, EmptyInput) {
  const EdgeTopology t = edge_topology({}, {});
  EXPECT_EQ(t.edges, 0);
  EXPECT_EQ(t.components, 0);
  EXPECT_EQ(t.min_edge_m, 0);
}

}  // namespace
}  // namespace thaw::meshio
