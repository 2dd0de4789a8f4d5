// Tests render/geometry/obj_loader.h: triangulation, indices, normals and bad files.
#include "render/geometry/obj_loader.h"

#include <gtest/gtest.h>

#include "base/error.h"

namespace thaw::render {
namespace {

TEST(ObjLoader, QuadIsTriangulatedAndNegativeIndicesWork) {
  const auto m = parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n", "quad.obj");
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_FALSE(m.has_normals());
  for (const auto& t : m.triangles)
    for (auto i : t) EXPECT_LT(i, 4u);
}

TEST(ObjLoader, NormalsAreKeptAndNormalised) {
  const auto m = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nf 1//1 2//1 3//1\n", "n.obj");
  ASSERT_TRUE(m.has_normals());
  EXPECT_FLOAT_EQ(m.normals[0].z, 1.0f);
}

TEST(ObjLoader, ReferenceMeshLoadsClosed) {
  const auto m = load_obj(std::string(THAW_SOURCE_DIR) + "/data/scenes/meshes/sphere_r0.7.obj");
  EXPECT_EQ(m.triangles.size(), 20480u);
  EXPECT_TRUE(m.has_normals());
  EXPECT_FALSE(closed_surface_problem(m).has_value());
  EXPECT_GT(signed_volume(m), 0.0);
}

void expect_error(const std::string& text, const std::string& fragment) {
  try {
    parse_obj(text, "bad.obj");
    FAIL() << "no error for: " << text;
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), "bad.obj");
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(ObjLoader, BadFilesAreUserErrors) {
  expect_error("", "no faces");
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "no faces");
  expect_error("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "line 2");
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n", "line 4: face refers to vertex 7");
  expect_error("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2: vertex needs 3 coordinates");
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0x 1 0\nf 1 2 3\n", "line 4");
}

// Issue 12: what tinyobjloader accepted (its warnings were dropped) is refused with its line.
TEST(ObjLoader, MalformedFacesAreRefusedWithTheirLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_error(tri + "f 1 2 4294967298\n", "line 4: face refers to vertex 4294967298");
  expect_error(tri + "f 1 2\n", "line 4: face needs at least 3 corners");
  expect_error(tri + "f 1 2 3 junk\n", "line 4: malformed vertex index 'junk'");
  expect_error(tri + "f 1 2 1.5\n", "line 4: malformed vertex index '1.5'");
  expect_error(tri + "f 1 2 3", "line 4: last line has no line end");
  // Finite in double, infinite in the renderer's float.
  expect_error("v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n", "non-finite");
}

TEST(ObjLoader, DirectoryIsNamedAsSuch) {
  try {
    load_obj(THAW_SOURCE_DIR);
    FAIL();
  } catch (const UserError& e) {
    EXPECT_EQ(e.problem(), "is a directory, expected an OBJ file");
  }
}

TEST(ObjLoader, MissingFileIsUserError) {
  EXPECT_THROW(load_obj("/nonexistent/thaw/mesh.obj"), UserError);
}

}  // namespace
}  // namespace thaw::render
