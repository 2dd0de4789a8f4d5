// Tests render/geometry/triangle_mesh.h: closedness, orientation, volume, smooth normals, the
// conversion from the mesh files' type.
#include "render/geometry/triangle_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "tests/render/test_util.h"

namespace thaw::render {
namespace {

TEST(TriangleMesh, IcosphereIsClosedAndOutward) {
  const TriangleMesh m = test::icosphere(2);
  EXPECT_EQ(m.triangles.size(), 320u);
  EXPECT_FALSE(validate_mesh(m).has_value());
  EXPECT_FALSE(closed_surface_problem(m).has_value());
  // Volume of the inscribed polyhedron: below 4/3 pi, above 90 % of it at 320 faces.
  const double v = signed_volume(m);
  EXPECT_LT(v, 4.0 / 3.0 * M_PI);
  EXPECT_GT(v, 0.9 * 4.0 / 3.0 * M_PI);
}

TEST(TriangleMesh, OpenMeshIsReported) {
  TriangleMesh m = test::icosphere(1);
  m.triangles.pop_back();
  const auto problem = closed_surface_problem(m);
  ASSERT_TRUE(problem.has_value());
  EXPECT_NE(problem->find("not closed"), std::string::npos);
}

TEST(TriangleMesh, FlippedFaceIsReported) {
  TriangleMesh m = test::icosphere(1);
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  EXPECT_TRUE(closed_surface_problem(m).has_value());
}

TEST(TriangleMesh, InwardMeshHasNegativeVolume) {
  TriangleMesh m = test::icosphere(1);
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  EXPECT_FALSE(closed_surface_problem(m).has_value());
  EXPECT_LT(signed_volume(m), 0.0);
}

TEST(TriangleMesh, SplitSeamVerticesAreWelded) {
  // Duplicate vertex 0 and let half of its triangles use the copy: still closed.
  TriangleMesh m = test::icosphere(1);
  m.positions.push_back(m.positions[0]);
  const auto copy = static_cast<std::uint32_t>(m.positions.size() - 1);
  int n = 0;
  for (auto& t : m.triangles)
    for (auto& i : t)
      if (i == 0 && (n++ % 2 == 0)) i = copy;
  EXPECT_FALSE(closed_surface_problem(m).has_value());
}

TEST(TriangleMesh, ValidateFindsBadIndicesAndNaN) {
  TriangleMesh m = test::icosphere(0);
  m.triangles[0][1] = 99;
  EXPECT_TRUE(validate_mesh(m).has_value());
  m = test::icosphere(0);
  m.positions[2].y = std::nanf("");
  EXPECT_TRUE(validate_mesh(m).has_value());
  EXPECT_TRUE(validate_mesh(TriangleMesh{}).has_value());
}

TEST(TriangleMesh, SmoothNormalsOfASpherePointOutward) {
  TriangleMesh m = test::icosphere(3);
  compute_smooth_normals(m);
  ASSERT_TRUE(m.has_normals());
  // At a vertex of a unit icosphere the area-weighted normal deviates from the radial direction
  // by much less than the angle between neighbouring vertices (~0.08 rad at 3 subdivisions).
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    EXPECT_GT(dot(m.normals[i], normalize(m.positions[i])), std::cos(0.08f));
}

TEST(TriangleMesh, TransformScalesThenTranslates) {
  TriangleMesh m;
  m.positions = {{1, 2, 3}};
  transform_mesh(m, 2.0, {1.0, 0.0, -1.0});
  EXPECT_EQ(m.positions[0], (Vec3{3, 4, 5}));
}

// The one conversion from the file type: positions rounded to the nearest float, normals made
// unit, indices kept; what single precision cannot hold is a UserError naming the source.
TEST(TriangleMesh, FromFileMeshRoundsToFloatAndNormalisesNormals) {
  meshio::TriangleMesh file;
  file.vertices = {{0.1, 0, 0}, {1, 0, 0}, {0, 1, 1e-30}};
  file.triangles = {{0, 1, 2}};
  file.normals = {{0, 0, 2}};
  file.normal_triangles = {{0, 0, 0}};
  const TriangleMesh m = from_file_mesh(file, "f.obj");
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[0].x, 0.1f);
  EXPECT_EQ(m.positions[2].z, 1e-30f);
  EXPECT_EQ(m.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  ASSERT_EQ(m.normals.size(), 1u);
  EXPECT_EQ(m.normals[0].z, 1.0f);
  EXPECT_EQ(m.normal_indices[0], (std::array<std::uint32_t, 3>{0, 0, 0}));

  meshio::TriangleMesh zero_normal = file;
  zero_normal.normals = {{0, 0, 0}};
  EXPECT_THROW(from_file_mesh(zero_normal, "f.obj"), UserError);
  meshio::TriangleMesh beyond_float = file;
  beyond_float.vertices[1][0] = 1e39;  // finite in double, infinite in float
  try {
    from_file_mesh(beyond_float, "f.obj");
    FAIL() << "no error";
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), "f.obj");
  }
}

}  // namespace
}  // namespace thaw::render
