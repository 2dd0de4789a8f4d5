// `thaw run` on the tiny 3D cube (tests/src/pipeline/data/tiny_cube.toml) and the tiny
// axisymmetric cylinder (tiny_cylinder.toml, its (r, y) field revolved) writes one OpenVDB file
// per step into DIR/handoff/vdb, placed where the hand-off meshes are: the world bounding box of
// the step-0 outer surface (the ice fraction's 1/2 isosurface: the mesh stage's OBJ placed as
// handoff/surfaces.json says, world = scale * file + translate; the largest surface of frame 0,
// since the outer surface encloses the others) against the box of
// the cell faces of the voxels holding at least half ice. Across a face, the 1/2 crossing of the
// fraction interpolated from a cell with f >= 1/2 to its neighbour with g < 1/2 is (f - 1/2) /
// (f - g) of a cell edge h beyond the first centre, so within h/2 of the cell face: each side
// within h/2 (the mesher's Taubin smoothing does not shrink; measured 0.14-0.17 h here). A wrong
// offset (the floor placement, ~ the cube's size) or a half-voxel error in the transform
// (h/2 + the measured gap) exceeds it. Revolved: the voxel beside the x (or z) axis at
// x = (m + 1/2) h, z = h/2 lies in ring m (sqrt((m + 1/2)^2 + 1/4) < m + 1), so the last ring
// holding half ice ends the voxels' box at that ring's outer face, as a cell face does in 3D;
// the mesh's polygonal outline falls short of its circle by R (1 - cos(pi / n)), ~0.03 h here.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "base/obj_reader.h"
#include "base/subprocess.h"
#include "tests/src/pipeline/run_test_support.h"

namespace thaw::pipeline {
namespace {
using namespace test;

class ThawRunVdb : public TempDirTest {
 protected:
  ThawRunVdb() : TempDirTest("thaw_test_vdb_run") {}
};

class ThawRunVdbOf : public ThawRunVdb, public ::testing::WithParamInterface<const char*> {};

TEST_P(ThawRunVdbOf, VolumesOfEveryStepSitWithTheMeshes) {
  const fs::path cube = fs::path(THAW_SOURCE_DIR) / "tests/src/pipeline/data" / GetParam();
  const fs::path out = m_dir / "out";
  for (const char* stage : {"simulate", "mesh", "inspect"}) {
    const auto r = run_process(
        {kThaw.string(), "run", cube.string(), "--out", out.string(), "--stage", stage, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  std::size_t steps = 0;
  for (const auto& e : fs::directory_iterator(out / "sim/fields")) steps += e.is_regular_file();
  ASSERT_GT(steps, 1u);
  for (std::size_t k = 0; k < steps; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "fields_%06zu.vdb", k);
    EXPECT_TRUE(fs::exists(out / "handoff/vdb" / name)) << name;
  }

  openvdb::initialize();
  openvdb::io::File file((out / "handoff/vdb/fields_000000.vdb").string());
  file.open();
  const auto ice = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("ice_fraction"));
  file.close();
  ASSERT_TRUE(ice);
  const double h = ice->voxelSize()[0];
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (auto v = ice->cbeginValueOn(); v; ++v)
    if (*v >= 0.5f) {
      const openvdb::Vec3d w = ice->indexToWorld(v.getCoord());
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], w[c] - h / 2);
        hi[c] = std::max(hi[c], w[c] + h / 2);
      }
    }
  // Frame 0's surfaces in world space, from the hand-off's listing of the mesh stage's files.
  std::ifstream listing_file(out / "handoff/surfaces.json");
  ASSERT_TRUE(listing_file) << "handoff/surfaces.json";
  const nlohmann::json listing = nlohmann::json::parse(listing_file);
  std::array<double, 3> mlo{}, mhi{};
  double largest = -1;
  for (const auto& surface : listing.at("surfaces")) {
    const auto& frame = surface.at("frames").at(0);
    if (frame.is_null()) continue;
    const meshio::TriangleMesh m = meshio::read_obj(out / frame.at("file").get<std::string>());
    if (m.vertices.empty()) continue;
    const double scale = frame.at("scale").get<double>();
    const auto translate = frame.at("translate_m").get<std::array<double, 3>>();
    std::array<double, 3> lo_w, hi_w;
    lo_w.fill(std::numeric_limits<double>::infinity());
    hi_w.fill(-std::numeric_limits<double>::infinity());
    for (const auto& p : m.vertices)
      for (int c = 0; c < 3; ++c) {
        const double w = scale * p[c] + translate[c];
        lo_w[c] = std::min(lo_w[c], w);
        hi_w[c] = std::max(hi_w[c], w);
      }
    const double extent = hi_w[0] - lo_w[0] + hi_w[1] - lo_w[1] + hi_w[2] - lo_w[2];
    if (extent > largest) {
      largest = extent;
      mlo = lo_w;
      mhi = hi_w;
    }
  }
  ASSERT_GT(largest, 0) << "no surface in frame 0 of handoff/surfaces.json";
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(mlo[c], lo[c], h / 2) << "axis " << c;
    EXPECT_NEAR(mhi[c], hi[c], h / 2) << "axis " << c;
  }
}

INSTANTIATE_TEST_SUITE_P(GridRuns, ThawRunVdbOf,
                         ::testing::Values("tiny_cube.toml", "tiny_cylinder.toml"));

}  // namespace
}  // namespace thaw::pipeline
