// Tests src/mesh/triangle_mesh.h: the one conversion between the mesher's mesh and the mesh
// files' type (base/obj_reader.h), and the enclosed volume and area of a known solid.
#include "src/mesh/triangle_mesh.h"

#include <gtest/gtest.h>

namespace thaw::mesh {
namespace {

// The unit cube [0,1]^3 as 12 outward triangles.
TriangleMesh unit_cube() {
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.faces = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
             {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {0, 4, 7}, {0, 7, 3}};
  return m;
}

TEST(TriangleMesh, CubeVolumeAndArea) {
  const TriangleMesh m = unit_cube();
  EXPECT_DOUBLE_EQ(enclosed_volume(m), 1.0);
  EXPECT_DOUBLE_EQ(surface_area(m), 6.0);
}

TEST(TriangleMesh, FileMeshRoundTripKeepsEverythingBitForBit) {
  TriangleMesh m = unit_cube();
  m.vertices[6] = {1.0000000000000002, 0.1, 1.0 / 3.0};
  set_angle_weighted_normals(m);
  const meshio::TriangleMesh file = to_file_mesh(m);
  EXPECT_EQ(file.vertices, m.vertices);
  ASSERT_EQ(file.triangles.size(), m.faces.size());
  EXPECT_EQ(file.triangles[3], (std::array<std::int64_t, 3>{4, 6, 7}));
  EXPECT_EQ(file.normals, m.normals);
  EXPECT_EQ(file.normal_triangles, file.triangles);  // vertex normals: indexed like the vertices
  const TriangleMesh back = from_file_mesh(file);
  EXPECT_EQ(back.vertices, m.vertices);
  EXPECT_EQ(back.faces, m.faces);
  EXPECT_EQ(back.normals, m.normals);

  const TriangleMesh plain = from_file_mesh(to_file_mesh(unit_cube()));
  EXPECT_TRUE(plain.normals.empty());
  EXPECT_EQ(plain.faces, unit_cube().faces);
}

// Converting into a file mesh that held a larger mesh with normals gives what a fresh conversion
// gives: every array replaced, none kept from before.
TEST(TriangleMesh, FileMeshIntoReusedStorageEqualsAFreshOne) {
  TriangleMesh with_normals = unit_cube();
  set_angle_weighted_normals(with_normals);
  meshio::TriangleMesh file;
  to_file_mesh(with_normals, file);
  TriangleMesh small;
  small.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  small.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  to_file_mesh(small, file);
  const meshio::TriangleMesh fresh = to_file_mesh(small);
  EXPECT_EQ(file.vertices, fresh.vertices);
  EXPECT_EQ(file.triangles, fresh.triangles);
  EXPECT_TRUE(file.normals.empty());
  EXPECT_TRUE(file.normal_triangles.empty());
}

// A file whose normals are not one per vertex, indexed like the vertices, has no vertex normals
// the mesher could keep: they are dropped, not misassigned.
TEST(TriangleMesh, FileNormalsWithTheirOwnIndicesAreNotTakenAsVertexNormals) {
  meshio::TriangleMesh file = to_file_mesh(unit_cube());
  file.normals.assign(file.vertices.size(), {0, 0, 1});
  file.normal_triangles.assign(file.triangles.size(), {0, 1, 2});
  EXPECT_TRUE(from_file_mesh(file).normals.empty());
  file.normal_triangles = file.triangles;
  file.normals.pop_back();
  EXPECT_TRUE(from_file_mesh(file).normals.empty());
}

}  // namespace
}  // namespace thaw::mesh
