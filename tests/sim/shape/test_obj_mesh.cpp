// The strict OBJ reader (sim/shape/obj_mesh.h): the shipped icosphere reads as closed and
// outward with the volume of its facets, its signed distance matches the sphere's to the facet
// sag, and open, non-manifold or inward meshes are refused naming the file and the key.
#include "sim/shape/obj_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "base/error.h"

namespace thaw::sim {
namespace {

namespace fs = std::filesystem;

const std::string kIcosphere = std::string(THAW_SOURCE_DIR) + "/data/shapes/icosphere.obj";

fs::path write_obj(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(THAW_BINARY_DIR) / "test-tmp" / "obj_mesh";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

const std::string kTetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";

void expect_refused(const fs::path& file, const std::string& fragment) {
  try {
    read_obj_mesh(file, 1.0, {0, 0, 0}, "s.toml", "shape.outer.file");
    FAIL() << "accepted " << file;
  } catch (const UserError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find("shape.outer.file"), std::string::npos) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(ObjMesh, IcosphereIsClosedOutwardAndNearlyASphere) {
  const ObjMesh m = read_obj_mesh(kIcosphere, 0.02, {0.01, 0, 0}, "s.toml", "shape.outer.file");
  EXPECT_EQ(m.triangles.size(), 1280u);
  // the file's header: enclosed volume 4.152740817 of the unit icosphere
  EXPECT_NEAR(m.volume(), 4.152740817093066 * std::pow(0.02, 3), 1e-15);
  // vertices on the sphere, facet centres at most the sag r (1 - cos(edge/2r)) ~ 0.6 % inside
  EXPECT_NEAR(m.signed_distance({0.01, 0.0, 0.0}), -0.02, 0.02 * 0.01);
  EXPECT_NEAR(m.signed_distance({0.05, 0.0, 0.0}), 0.02, 0.02 * 0.01);
  EXPECT_LT(m.signed_distance({0.01, 0.019, 0.0}), 0);
  EXPECT_GT(m.signed_distance({0.01, 0.021, 0.0}), 0);
}

TEST(ObjMesh, OpenNonManifoldAndInwardMeshesAreRefused) {
  expect_refused(write_obj("open.obj", kTetra + "f 1 3 2\nf 1 2 4\nf 1 4 3\n"),
                 "at least 4 triangles");
  expect_refused(write_obj("hole.obj", kTetra + "v 1 1 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 5\n"),
                 "not closed");
  expect_refused(write_obj("inward.obj", kTetra + "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n"),
                 "negative or zero volume");
  expect_refused(write_obj("twice.obj", kTetra + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\nf 1 3 2\n"),
                 "not manifold");
  expect_refused(write_obj("index.obj", kTetra + "f 1 3 9\n"),
                 "line 5: face refers to vertex 9 but the file has only 4 vertices");
  expect_refused(fs::path(THAW_BINARY_DIR) / "test-tmp" / "obj_mesh" / "missing.obj",
                 "no such file");
  // the valid tetrahedron reads
  EXPECT_NO_THROW(
      read_obj_mesh(write_obj("tetra.obj", kTetra + "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n"), 1.0,
                    {0, 0, 0}, "s.toml", "k"));
}

}  // namespace
}  // namespace thaw::sim
