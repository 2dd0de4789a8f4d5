// Tests of src/inspect/field_export: the grid solver's fields read back by VTK's own XML readers
// (geometry of the image and every cell value exact: floats are stored as floats), and the .pvd
// series lists the steps at their simulated times.
#include "src/inspect/field_export.h"

#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataReader.h>

#include <fstream>
#include <sstream>

#include "sim/format/grid_field_file.h"
#include "tests/src/inspect/test_meshes.h"

namespace thaw::inspect {
namespace {
namespace fs = std::filesystem;

sim::GridField field(double time_s) {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::cartesian3d;
  f.cells = {3, 2, 2};
  f.origin_m = {-0.015, 0.0, -0.01};
  f.spacing_m = 0.01;
  f.time_s = time_s;
  for (std::size_t c = 0; c < f.cell_count(); ++c) {
    f.temperature_c.push_back(-5.0f + 0.5f * static_cast<float>(c) + static_cast<float>(time_s));
    f.ice_fraction.push_back(static_cast<float>(c % 3) / 2.0f);
    f.water_fraction.push_back(1.0f - static_cast<float>(c % 3) / 2.0f);
  }
  return f;
}

TEST(FieldExport, FieldsReadBackByVtkWithTheSolversCells) {
  testing::ScratchDir dir("fields");
  fs::create_directories(dir.path() / "sim/fields");
  const sim::GridField a = field(0.0), b = field(30.0);
  sim::write_grid_field(dir.path() / "sim/fields/step_000000.grid", a);
  sim::write_grid_field(dir.path() / "sim/fields/step_000001.grid", b);
  const fs::path pvd = dir.path() / "out/fields.pvd";
  fs::create_directories(pvd.parent_path());
  EXPECT_EQ(write_field_series(dir.path() / "sim", pvd), 2);
  std::stringstream text;
  text << std::ifstream(pvd).rdbuf();
  EXPECT_NE(text.str().find("timestep=\"30\" part=\"0\" file=\"fields_vti/step_000001.vti\""),
            std::string::npos)
      << text.str();

  vtkNew<vtkXMLImageDataReader> reader;
  const fs::path vti = pvd.parent_path() / "fields_vti/step_000001.vti";
  reader->SetFileName(vti.c_str());
  reader->Update();
  ASSERT_EQ(reader->GetErrorCode(), 0u);
  vtkImageData* image = reader->GetOutput();
  int dims[3];
  image->GetDimensions(dims);
  EXPECT_EQ(dims[0], 4);
  EXPECT_EQ(dims[1], 3);
  EXPECT_EQ(dims[2], 3);
  double origin[3], spacing[3];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(origin[k], b.origin_m[k]);
    EXPECT_EQ(spacing[k], b.spacing_m);
  }
  ASSERT_EQ(image->GetNumberOfCells(), static_cast<vtkIdType>(b.cell_count()));
  for (const char* name : {"temperature_c", "ice_fraction", "water_fraction"}) {
    vtkDataArray* array = image->GetCellData()->GetArray(name);
    ASSERT_NE(array, nullptr) << name;
    const auto& expect = std::string(name) == "temperature_c"  ? b.temperature_c
                         : std::string(name) == "ice_fraction" ? b.ice_fraction
                                                               : b.water_fraction;
    for (int kk = 0; kk < 2; ++kk)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
          // VTK's cell (i, j, k) is the solver's cell (i, j, k): same flat order.
          int ijk[3] = {i, j, kk};
          const vtkIdType cell = image->ComputeCellId(ijk);
          EXPECT_EQ(array->GetTuple1(cell), expect[b.index(i, j, kk)]) << name;
        }
  }
}

// The fields sit where the meshes of meshes.pvd do (the run's placement of each step), and every
// array is inline (base64 in its DataArray): Debian 12's ParaView 5.11 cannot read an appended
// section, raw or base64, once expat's reparse deferral is in (data/paraview/check_in_debian.sh).
TEST(FieldExport, FieldsArePlacedLikeTheMeshesWithTheirArraysInline) {
  testing::ScratchDir dir("fields_placed");
  fs::create_directories(dir.path() / "sim/fields");
  const sim::GridField a = field(0.0);
  sim::write_grid_field(dir.path() / "sim/fields/step_000007.grid", a);
  const fs::path pvd = dir.path() / "out/fields.pvd";
  fs::create_directories(pvd.parent_path());
  std::vector<long> asked;
  const std::array<double, 3> offset{0.25, 0.0125, -0.5};
  EXPECT_EQ(write_field_series(dir.path() / "sim", pvd, {},
                               [&](long step) {
                                 asked.push_back(step);
                                 return offset;
                               }),
            1);
  EXPECT_EQ(asked, std::vector<long>{7});
  const fs::path vti = pvd.parent_path() / "fields_vti/step_000007.vti";
  std::stringstream text;
  text << std::ifstream(vti).rdbuf();
  EXPECT_EQ(text.str().find("AppendedData"), std::string::npos);
  EXPECT_NE(text.str().find("format=\"binary\""), std::string::npos);
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(vti.c_str());
  reader->Update();
  ASSERT_EQ(reader->GetErrorCode(), 0u);
  double origin[3];
  reader->GetOutput()->GetOrigin(origin);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(origin[k], a.origin_m[k] + offset[k]) << k;
  EXPECT_EQ(reader->GetOutput()->GetCellData()->GetArray("temperature_c")->GetTuple1(5),
            a.temperature_c[5]);
}

// A run with flow: the velocity is a 3-component cell array (the active vectors, for ParaView's
// Glyph and Stream Tracer), each cell's (u_x, u_y, u_z) exact; a run without has no such array.
TEST(FieldExport, VelocityIsAThreeComponentCellArrayOnlyWhenTheRunFlows) {
  testing::ScratchDir dir("fields_velocity");
  sim::GridField moving = field(10.0);
  for (std::size_t c = 0; c < moving.cell_count(); ++c)
    for (int d = 0; d < 3; ++d)
      moving.velocity_m_s.push_back(1e-4f * static_cast<float>((d + 1) * (c + 1)) *
                                    (d == 1 ? -1.0f : 1.0f));
  const sim::GridField still = field(10.0);
  for (const sim::GridField* f : {static_cast<const sim::GridField*>(&moving), &still}) {
    const fs::path vti = dir.path() / (f->has_velocity() ? "moving.vti" : "still.vti");
    write_vti(vti, *f);
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName(vti.c_str());
    reader->Update();
    ASSERT_EQ(reader->GetErrorCode(), 0u);
    vtkCellData* cells = reader->GetOutput()->GetCellData();
    vtkDataArray* u = cells->GetArray("velocity_m_s");
    if (!f->has_velocity()) {
      EXPECT_EQ(u, nullptr);
      EXPECT_EQ(cells->GetNumberOfArrays(), 3);
      continue;
    }
    ASSERT_NE(u, nullptr);
    EXPECT_EQ(cells->GetVectors(), u);
    ASSERT_EQ(u->GetNumberOfComponents(), 3);
    ASSERT_EQ(u->GetNumberOfTuples(), static_cast<vtkIdType>(f->cell_count()));
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        int ijk[3] = {i, j, 1};
        const vtkIdType cell = reader->GetOutput()->ComputeCellId(ijk);
        for (int d = 0; d < 3; ++d)
          EXPECT_EQ(u->GetComponent(cell, d), f->velocity_m_s[3 * f->index(i, j, 1) + d]);
      }
  }
}

TEST(FieldExport, NoFieldsWritesNothing) {
  testing::ScratchDir dir("no_fields");
  EXPECT_EQ(write_field_series(dir.path(), dir.path() / "fields.pvd"), 0);
  EXPECT_FALSE(fs::exists(dir.path() / "fields.pvd"));
}

}  // namespace
}  // namespace thaw::inspect
