// The OpenVDB hand-off (src/pipeline/handoff_vdb.h) read back with OpenVDB's own reader: the grid
// names, every voxel's value (exactly the field's float), which voxels are active, the time
// metadata, and the transform (voxel size = the cell edge; voxel (i, j, k) at the cell's centre
// plus the placement offset, to double round-off: 1e-12 m on coordinates below 1 m).
#include "src/pipeline/handoff_vdb.h"

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "base/error.h"
#include "sim/format/grid_field_file.h"

namespace thaw::pipeline {
namespace {
namespace fs = std::filesystem;

sim::GridField analytic_field() {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::cartesian3d;
  f.cells = {5, 4, 3};
  f.origin_m = {-0.01, 0.02, 0.005};
  f.spacing_m = 0.002;
  f.time_s = 123.456789;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 5; ++i) {
        f.temperature_c.push_back(static_cast<float>(-5 + 1.5 * i + 0.25 * j - 0.125 * k));
        f.ice_fraction.push_back(i >= 1 && i <= 3 ? 0.25f * static_cast<float>(j) : 0.0f);
        f.water_fraction.push_back(i == 2 && j == 1 ? 0.5f : 0.0f);
      }
  return f;
}

class HandoffVdb : public ::testing::Test {
 protected:
  void SetUp() override {
    openvdb::initialize();
    m_dir = fs::temp_directory_path() / ("thaw_test_vdb_" + std::to_string(::getpid()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  fs::path m_dir;
};

TEST_F(HandoffVdb, GridsValuesAndTransformReadBackByOpenVdb) {
  const sim::GridField f = analytic_field();
  const std::array<double, 3> offset{0.1, 0.2, -0.3};
  const fs::path path = m_dir / vdb_file_name(7);
  EXPECT_EQ(path.filename(), "fields_000007.vdb");
  write_field_vdb(path, f, offset);

  openvdb::io::File file(path.string());
  file.open();
  EXPECT_EQ(file.getMetadata()->metaValue<double>("time_s"), f.time_s);
  const std::pair<const char*, const std::vector<float>*> grids[] = {
      {"temperature_c", &f.temperature_c},
      {"ice_fraction", &f.ice_fraction},
      {"water_fraction", &f.water_fraction}};
  for (const auto& [name, values] : grids) {
    ASSERT_TRUE(file.hasGrid(name)) << name;
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(name));
    ASSERT_TRUE(grid) << name;
    const openvdb::Vec3d voxel = grid->voxelSize();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(voxel[c], f.spacing_m, 1e-15) << name;
    std::size_t nonzero = 0;
    for (int k = 0; k < f.cells[2]; ++k)
      for (int j = 0; j < f.cells[1]; ++j)
        for (int i = 0; i < f.cells[0]; ++i) {
          const float expect = (*values)[f.index(i, j, k)];
          nonzero += expect != 0.0f;
          const openvdb::Coord ijk(i, j, k);
          EXPECT_EQ(grid->tree().getValue(ijk), expect) << name << " " << i << j << k;
          const openvdb::Vec3d w = grid->indexToWorld(ijk);
          const int n[3] = {i, j, k};
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(w[c], f.origin_m[c] + (n[c] + 0.5) * f.spacing_m + offset[c], 1e-12);
        }
    // temperature: every cell; the fractions: the cells holding some (background 0 elsewhere)
    const bool dense = std::string(name) == "temperature_c";
    EXPECT_EQ(grid->activeVoxelCount(), dense ? f.cell_count() : nonzero) << name;
    EXPECT_EQ(grid->background(), 0.0f);
    EXPECT_EQ(grid->tree().getValue(openvdb::Coord(-1, 0, 0)), 0.0f);  // outside: background
  }
  file.close();
  for (const auto& e : fs::directory_iterator(m_dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(HandoffVdb, SequenceOfA3dRunAndOfARevolvedAxisymmetricRun) {
  sim::GridField f = analytic_field();
  fs::create_directories(m_dir / "sim" / "fields");
  sim::write_grid_field(m_dir / "sim" / "fields" / "step_000000.grid", f);
  f.time_s = 200;
  sim::write_grid_field(m_dir / "sim" / "fields" / "step_000003.grid", f);
  const auto offset_of = [](long step) { return std::array<double, 3>{0, 0.01 * step, 0}; };
  EXPECT_EQ(write_vdb_sequence(m_dir / "sim", m_dir / "vdb", offset_of), 2);
  EXPECT_TRUE(fs::exists(m_dir / "vdb" / "fields_000000.vdb"));
  openvdb::io::File file((m_dir / "vdb" / "fields_000003.vdb").string());
  file.open();
  EXPECT_EQ(file.getMetadata()->metaValue<double>("time_s"), 200.0);
  const auto grid = file.readGrid("ice_fraction");
  EXPECT_NEAR(grid->indexToWorld(openvdb::Coord(0, 0, 0))[1], 0.02 + 0.001 + 0.03, 1e-12);
  file.close();

  sim::GridField a = analytic_field();
  a.geometry = sim::GridField::Geometry::axisymmetric;
  a.cells = {5, 4, 1};
  a.origin_m = {0, 0.02, 0};
  a.temperature_c.resize(a.cell_count()), a.ice_fraction.resize(a.cell_count());
  a.water_fraction.resize(a.cell_count());
  fs::create_directories(m_dir / "axi" / "fields");
  sim::write_grid_field(m_dir / "axi" / "fields" / "step_000000.grid", a);
  EXPECT_EQ(write_vdb_sequence(m_dir / "axi", m_dir / "axi_vdb", offset_of), 1);
  openvdb::io::File revolved((m_dir / "axi_vdb" / "fields_000000.vdb").string());
  revolved.open();
  const auto t = openvdb::gridPtrCast<openvdb::FloatGrid>(revolved.readGrid("temperature_c"));
  EXPECT_EQ(t->activeVoxelCount(), 10u * 4u * 10u);  // 2 nr x ny x 2 nr, every cell
  // The cell beside the axis (x = z = h/2, ring 0) and one on the x axis in ring 3.
  EXPECT_EQ(t->tree().getValue(openvdb::Coord(5, 2, 5)), a.temperature_c[a.index(0, 2, 0)]);
  EXPECT_EQ(t->tree().getValue(openvdb::Coord(8, 1, 5)), a.temperature_c[a.index(3, 1, 0)]);
  EXPECT_NEAR(t->indexToWorld(openvdb::Coord(5, 0, 5))[0], 0.5 * a.spacing_m, 1e-12);
  revolved.close();
  // A 1D run has no fields: nothing.  // A 1D run has no fields: nothing.
  EXPECT_EQ(write_vdb_sequence(m_dir / "nothing", m_dir / "none_vdb", offset_of), 0);
}

// Revolving an (r, y) field about y: every cell takes its centre's ring, so the result is
// symmetric under x -> -x, z -> -z and x <-> z, constant along y as the field is, and the
// corners beyond the outermost ring take that ring (the solver's outer air).
TEST(RevolvedField, EveryCellTakesTheRingItsCentreLiesIn) {
  sim::GridField a;
  a.geometry = sim::GridField::Geometry::axisymmetric;
  a.cells = {4, 3, 1};
  a.origin_m = {0, -0.01, 0};
  a.spacing_m = 0.5e-3;
  a.time_s = 9;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) {
      a.temperature_c.push_back(static_cast<float>(10 * i + j));
      a.ice_fraction.push_back(i < 2 ? 1.0f : 0.0f);
      a.water_fraction.push_back(i == 2 ? 0.5f : 0.0f);
    }
  const sim::GridField f = revolved_field(a);
  EXPECT_EQ(f.geometry, sim::GridField::Geometry::cartesian3d);
  EXPECT_EQ(f.cells, (std::array<int, 3>{8, 3, 8}));
  EXPECT_EQ(f.origin_m, (std::array<double, 3>{-2e-3, -0.01, -2e-3}));
  EXPECT_EQ(f.spacing_m, a.spacing_m);
  EXPECT_EQ(f.time_s, 9);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 8; ++i) {
        const double x = f.origin_m[0] + (i + 0.5) * f.spacing_m;
        const double z = f.origin_m[2] + (k + 0.5) * f.spacing_m;
        const int ring = std::min(3, static_cast<int>(std::hypot(x, z) / a.spacing_m));
        EXPECT_EQ(f.temperature_c[f.index(i, j, k)], a.temperature_c[a.index(ring, j, 0)]);
        EXPECT_EQ(f.ice_fraction[f.index(i, j, k)], a.ice_fraction[a.index(ring, j, 0)]);
        EXPECT_EQ(f.water_fraction[f.index(i, j, k)], a.water_fraction[a.index(ring, j, 0)]);
        EXPECT_EQ(f.temperature_c[f.index(i, j, k)], f.temperature_c[f.index(7 - i, j, k)]);
        EXPECT_EQ(f.temperature_c[f.index(i, j, k)], f.temperature_c[f.index(k, j, i)]);
      }
  // Ice (rings 0-1: r < 1 mm) fills the cells whose centres are within 1 mm of the axis.
  EXPECT_EQ(f.ice_fraction[f.index(3, 0, 3)], 1.0f);  // centre at r = 0.35 mm
  EXPECT_EQ(f.ice_fraction[f.index(0, 0, 0)], 0.0f);  // corner, r = 2.47 mm: the outer ring
  EXPECT_EQ(f.temperature_c[f.index(0, 2, 0)], 32.0f);
  // A cartesian field passes through unchanged.
  EXPECT_EQ(revolved_field(f).temperature_c, f.temperature_c);
}

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Issue 27: OpenVDB puts a new random UUID into every file's header, so two runs and any resume
// differed in handoff/vdb/. Now the same field gives the same bytes, written at another time and
// under another name, still a UUID that OpenVDB reads; another field gives another UUID.
TEST_F(HandoffVdb, SameFieldGivesTheSameBytesAndAnotherFieldAnotherUuid) {
  const sim::GridField f = analytic_field();
  write_field_vdb(m_dir / "a.vdb", f, {0, 0, 0});
  write_field_vdb(m_dir / "b.vdb", f, {0, 0, 0});
  const std::string a = file_bytes(m_dir / "a.vdb"), b = file_bytes(m_dir / "b.vdb");
  ASSERT_GT(a.size(), 57u);
  EXPECT_EQ(a, b);
  sim::GridField g = f;
  g.time_s += 1;
  write_field_vdb(m_dir / "c.vdb", g, {0, 0, 0});
  const std::string c = file_bytes(m_dir / "c.vdb");
  // The UUID: 36 characters after the 21-byte start of the header (io/Archive.cc).
  EXPECT_NE(a.substr(21, 36), c.substr(21, 36));
  openvdb::io::File file((m_dir / "c.vdb").string());
  file.open();
  const std::string uuid = file.getUniqueTag();
  EXPECT_EQ(uuid, c.substr(21, 36));
  EXPECT_EQ(uuid[14], '8');  // RFC 9562 version 8 (custom)
  EXPECT_EQ(file.getMetadata()->metaValue<double>("time_s"), g.time_s);
  EXPECT_TRUE(file.hasGrid("ice_fraction"));
  file.close();
  for (const auto& e : fs::directory_iterator(m_dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp-"), std::string::npos) << e.path();
}

TEST_F(HandoffVdb, UnwritableFolderIsAUserError) {
  EXPECT_THROW(write_field_vdb(m_dir / "missing" / "x.vdb", analytic_field(), {0, 0, 0}),
               UserError);
}

}  // namespace
}  // namespace thaw::pipeline
