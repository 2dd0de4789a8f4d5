// Tests of src/inspect/pvd_writer: the .pvd collection round-trips through VTK's XML readers
// with the simulated times, the parts are inner/outer, vanished surfaces are empty data sets, and
// the collection is valid after every single step (as after an interrupted run).
#include "src/inspect/pvd_writer.h"

#include <gtest/gtest.h>

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataReader.h>
#include <atomic>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>

#include "base/error.h"
#include "base/outcome.h"
#include "sim/format/grid_field_file.h"
#include "tests/base/file_size_limit.h"
#include "tests/src/inspect/test_meshes.h"

namespace thaw::inspect {
namespace {
namespace fs = std::filesystem;

struct PvdEntry {
  double time_s;
  int part;
  std::string file;
};

/// Parses a .pvd with VTK's own XML parser (what ParaView's PVD reader builds on).
std::vector<PvdEntry> parse_pvd(const fs::path& pvd) {
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(pvd.c_str());
  EXPECT_EQ(parser->Parse(), 1) << pvd;
  vtkXMLDataElement* root = parser->GetRootElement();
  std::vector<PvdEntry> out;
  if (root == nullptr) return out;
  EXPECT_STREQ(root->GetName(), "VTKFile");
  EXPECT_STREQ(root->GetAttribute("type"), "Collection");
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  if (collection == nullptr) return out;
  for (int i = 0; i < collection->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = collection->GetNestedElement(i);
    EXPECT_STREQ(e->GetName(), "DataSet");
    PvdEntry entry{};
    EXPECT_TRUE(e->GetScalarAttribute("timestep", entry.time_s));
    EXPECT_TRUE(e->GetScalarAttribute("part", entry.part));
    entry.file = e->GetAttribute("file");
    out.push_back(entry);
  }
  return out;
}

vtkSmartPointer<vtkPolyData> read_vtp(const fs::path& file) {
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(file.c_str());
  reader->Update();
  EXPECT_EQ(reader->GetErrorCode(), 0u) << file;
  return reader->GetOutput();
}

TEST(PvdWriter, SeriesRoundTripsThroughVtkReaders) {
  testing::ScratchDir dir("pvd");
  const auto rows = testing::write_sphere_simulation(dir.path() / "sim", 4);
  const fs::path pvd = dir.path() / "out" / "melt.pvd";
  std::int64_t calls = 0;
  write_pvd_series(dir.path() / "sim", pvd, [&](std::int64_t, std::int64_t) { ++calls; });
  EXPECT_EQ(calls, 4);
  const auto entries = parse_pvd(pvd);
  ASSERT_EQ(entries.size(), 8u);
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const PvdEntry& e = entries[k];
    const auto& row = rows[k / 2];
    EXPECT_EQ(e.time_s, row.time_s);  // %.17g round-trips doubles exactly
    EXPECT_EQ(e.part, static_cast<int>(k % 2));
    const auto poly = read_vtp(pvd.parent_path() / e.file);
    const bool vanished = e.part == 0 && row.inner_radius_m == 0;
    EXPECT_EQ(poly->GetNumberOfPolys(), vanished ? 0 : 1280) << e.file;
    if (!vanished) {
      // The points are the OBJ's, in double precision: the first is the icosahedron vertex
      // (-1, phi, 0)/|.| scaled by the radius.
      const double r = e.part == 0 ? row.inner_radius_m : row.outer_radius_m;
      const auto expect = testing::icosphere(r, 3).vertices[0];
      double p[3];
      poly->GetPoint(0, p);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(p[c], expect[c]);
    }
  }
  // No temporary files are left behind.
  for (const auto& f : fs::recursive_directory_iterator(dir.path() / "out"))
    EXPECT_EQ(f.path().string().find(".tmp-"), std::string::npos) << f.path();
}

TEST(PvdWriter, PointNormalsAndPlacementReadBackByVtk) {
  testing::ScratchDir dir("pvd_normals");
  const auto rows = testing::write_sphere_simulation(dir.path() / "sim", 2);
  const fs::path pvd = dir.path() / "out" / "melt.pvd";
  const std::array<double, 3> offset{0.25, -0.5, 1.0};
  write_pvd_series(dir.path() / "sim", pvd, {}, [&](long) { return offset; });
  const auto entries = parse_pvd(pvd);
  ASSERT_EQ(entries.size(), 4u);
  const auto poly = read_vtp(pvd.parent_path() / entries[1].file);  // step 0, outer sphere
  const double r = rows[0].outer_radius_m;
  ASSERT_GT(poly->GetNumberOfPoints(), 0);
  vtkDataArray* normals = poly->GetPointData()->GetNormals();
  ASSERT_NE(normals, nullptr);
  EXPECT_STREQ(normals->GetName(), "Normals");
  ASSERT_EQ(normals->GetNumberOfTuples(), poly->GetNumberOfPoints());
  double h_max = 0;  // the longest edge [m]
  const auto mesh = testing::icosphere(r, 3);
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const auto& a = mesh.vertices[static_cast<std::size_t>(t[c])];
      const auto& b = mesh.vertices[static_cast<std::size_t>(t[(c + 1) % 3])];
      h_max = std::max(h_max, std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]));
    }
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    double p[3], n[3];
    poly->GetPoint(i, p);
    normals->GetTuple(i, n);
    // Placed: the icosphere's vertices are on the sphere of radius r about `offset`.
    const double d[3] = {p[0] - offset[0], p[1] - offset[1], p[2] - offset[2]};
    const double dist = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    EXPECT_NEAR(dist, r, 1e-12 * r);
    // Unit normals. The exact sphere's normal is d / r. The area-weighted normal is a convex
    // combination of the adjacent faces' normals, and the plane of a face with a corner on the
    // sphere tilts from that corner's tangent plane by at most the angle its longest edge
    // subtends, h / r: so the angle to d / r is at most h_max / r. A wrong orientation or
    // index would be off by ~1 rad or more.
    EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-12);
    const double cosine = (n[0] * d[0] + n[1] * d[1] + n[2] * d[2]) / dist;
    EXPECT_GT(cosine, std::cos(h_max / r)) << "vertex " << i;
  }
}

// Issue 13: a grid run's surfaces carry the material temperature at their vertices. A field
// linear in space is interpolated exactly (field_probe.h), so each vertex's value is that linear
// function at the vertex in the field's frame, i.e. before the placement offset; the tolerance is
// the float storage of the field (max|T| * 2^-24 < 1e-6 here). A step without a field has none.
TEST(PvdWriter, GridStepsCarryTheSurfaceTemperatureReadBackByVtk) {
  testing::ScratchDir dir("pvd_temperature");
  testing::write_sphere_simulation(dir.path() / "sim", 2);
  const auto linear = [](double x, double y, double z) { return -3 + 40 * x + 60 * y - 80 * z; };
  sim::GridField field;
  field.cells = {8, 8, 8};
  field.origin_m = {-0.02, -0.02, -0.02};
  field.spacing_m = 0.005;
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const auto c = [&](int n, int a) { return field.origin_m[a] + (n + 0.5) * 0.005; };
        field.temperature_c.push_back(static_cast<float>(linear(c(i, 0), c(j, 1), c(k, 2))));
        field.ice_fraction.push_back(1.0f);
        field.water_fraction.push_back(0.0f);
      }
  fs::create_directories(dir.path() / "sim" / "fields");
  sim::write_grid_field(dir.path() / "sim" / "fields" / "step_000000.grid", field);
  const fs::path pvd = dir.path() / "out" / "melt.pvd";
  const std::array<double, 3> offset{0.1, 0.2, -0.3};
  write_pvd_series(dir.path() / "sim", pvd, {}, [&](long) { return offset; });
  const auto entries = parse_pvd(pvd);
  ASSERT_EQ(entries.size(), 4u);
  for (std::size_t e = 0; e < 2; ++e) {  // step 0: inner and outer
    const auto poly = read_vtp(pvd.parent_path() / entries[e].file);
    vtkDataArray* t = poly->GetPointData()->GetArray("temperature_c");
    ASSERT_NE(t, nullptr) << entries[e].file;
    EXPECT_EQ(poly->GetPointData()->GetScalars(), t);  // ParaView colours by it
    ASSERT_EQ(t->GetNumberOfTuples(), poly->GetNumberOfPoints());
    ASSERT_GT(poly->GetNumberOfPoints(), 0);
    for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
      double p[3];
      poly->GetPoint(i, p);
      EXPECT_NEAR(t->GetTuple1(i), linear(p[0] - offset[0], p[1] - offset[1], p[2] - offset[2]),
                  1e-6)
          << i;
    }
  }
  const auto later = read_vtp(pvd.parent_path() / entries[3].file);  // step 1: no field
  EXPECT_EQ(later->GetPointData()->GetArray("temperature_c"), nullptr);
}

// Issue 12: an export that stops half-way (disk full, interrupt) leaves no partial .pvd: the
// collection is written once, by commit(), after every data set is on disk.
TEST(PvdWriter, CollectionIsWrittenOnlyOnCommit) {
  testing::ScratchDir dir("pvd");
  const fs::path pvd = dir.path() / "live.pvd";
  PvdWriter writer(pvd);
  const TriangleMesh a = testing::icosphere(1.0, 1), b = testing::icosphere(2.0, 1);
  writer.add(0, 0.0, SurfacePart::inner, &a);
  writer.add(0, 0.0, SurfacePart::outer, &b);
  writer.add(1, 2.5, SurfacePart::inner, nullptr);
  EXPECT_FALSE(fs::exists(pvd));
  writer.commit();
  const auto entries = parse_pvd(pvd);
  ASSERT_EQ(entries.size(), 3u);
  EXPECT_EQ(entries[2].time_s, 2.5);
  EXPECT_EQ(read_vtp(pvd.parent_path() / entries[2].file)->GetNumberOfPoints(), 0);
  // Re-adding a step replaces its entry instead of duplicating it.
  writer.add(1, 2.5, SurfacePart::inner, &a);
  writer.commit();
  EXPECT_EQ(parse_pvd(pvd).size(), 3u);
}

// A VTK write failure is one UserError carrying VTK's reason; nothing is printed by VTK itself.
TEST(PvdWriter, VtkWriteFailureIsOneUserErrorWithoutVtkOutput) {
  testing::ScratchDir dir("pvd");
  const TriangleMesh a = testing::icosphere(1.0, 1);
  ::testing::internal::CaptureStderr();
  // /dev/full: every write fails with ENOSPC, as on a full disk.
  std::string what;
  try {
    write_vtp("/dev/full/x.vtp", a);
  } catch (const UserError& e) {
    what = e.what();
  }
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(err, "");
  // One thaw line naming the file, without VTK's source location and pipeline dump (VTK writes
  // into memory, thaw writes the file: write_vtp).
  EXPECT_EQ(what.rfind("/dev/full/x.vtp: ", 0), 0u) << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  for (const char* noise : {"ERROR: In", ".cxx", "vtkInformation", "Debug: Off", "(0x"})
    EXPECT_EQ(what.find(noise), std::string::npos) << noise << " in " << what;
}

// Issue 12: a series export on a full disk leaves neither a .pvd nor a partial folder of data
// sets (nor temporaries) and says so in one line naming the file.
TEST(PvdWriter, FullDiskLeavesNoPartialSeries) {
  testing::ScratchDir dir("pvd");
  testing::write_sphere_simulation(dir.path() / "sim", 3);
  const fs::path out = dir.path() / "out";
  fs::create_directories(out);
  std::string what;
  try {
    const ::thaw::testing::FileSizeLimit full_disk(2000);  // below one .vtp of these spheres
    write_pvd_series(dir.path() / "sim", out / "series.pvd");
  } catch (const UserError& e) {
    what = e.what();
  }
  EXPECT_NE(what.find((out / "series_vtp" / "step_").string()), std::string::npos) << what;
  EXPECT_EQ(what.find(".tmp-"), std::string::npos) << what;
  EXPECT_TRUE(fs::is_empty(out)) << fs::directory_iterator(out)->path();
}

std::string file_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// thaw run's use: each step placed by its own outer surface (resting on y = 0 by its lowest
// vertex), and every surface handed on as written, each OBJ read once; steps on two threads
// give the same files as on one.
TEST(PvdWriter, OptionsPlaceByTheOuterSurfaceAndHandEverySurfaceOn) {
  testing::ScratchDir dir("pvd_options");
  const auto rows = testing::write_sphere_simulation(dir.path() / "sim", 4);
  std::string bytes[2];
  for (const int threads : {1, 2}) {
    std::mutex mutex;
    std::map<std::pair<long, int>, std::optional<TriangleMesh>> seen;
    PvdSeriesOptions options;
    options.placement = [&](const MeshedStep& s, const TriangleMesh* outer) {
      EXPECT_NE(outer, nullptr) << s.step;  // every outer sphere of this series exists
      double lowest = 0;
      for (const auto& v : outer->vertices) lowest = std::min(lowest, v[1]);
      return std::array<double, 3>{0.5, -lowest, 0};
    };
    options.surface = [&](const MeshedStep& s, SurfacePart part, const TriangleMesh* mesh) {
      const std::lock_guard<std::mutex> lock(mutex);
      EXPECT_TRUE(seen.emplace(std::pair(s.step, static_cast<int>(part)),
                               mesh ? std::optional(*mesh) : std::nullopt)
                      .second);
    };
    options.threads = threads;
    const fs::path pvd = dir.path() / ("out" + std::to_string(threads)) / "melt.pvd";
    write_pvd_series(dir.path() / "sim", pvd, options);
    ASSERT_EQ(seen.size(), 8u);
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const long step = rows[k].step;
      const auto& outer = seen.at({step, 1});
      ASSERT_TRUE(outer.has_value());
      double lowest = 1;
      for (const auto& v : outer->vertices) lowest = std::min(lowest, v[1]);
      EXPECT_EQ(lowest, 0.0) << step;  // x + (-x) is exactly 0
      // What the hook got is what the .vtp holds.
      for (const int part : {0, 1}) {
        const auto& mesh = seen.at({step, part});
        char name[64];
        std::snprintf(name, sizeof name, "melt_vtp/step_%06ld_%s.vtp", step,
                      part == 0 ? "inner" : "outer");
        const auto poly = read_vtp(pvd.parent_path() / name);
        ASSERT_EQ(poly->GetNumberOfPoints(),
                  mesh ? static_cast<vtkIdType>(mesh->vertices.size()) : 0)
            << name;
        for (vtkIdType i = 0; mesh && i < poly->GetNumberOfPoints(); ++i) {
          double p[3];
          poly->GetPoint(i, p);
          for (int c = 0; c < 3; ++c) EXPECT_EQ(p[c], mesh->vertices[i][c]) << name;
        }
        bytes[threads - 1] += file_bytes(pvd.parent_path() / name);
      }
    }
    bytes[threads - 1] += file_bytes(pvd);
  }
  EXPECT_EQ(bytes[0], bytes[1]);
}

// A failing step (here the hook's) fails the series after the others were attempted, and
// nothing is committed: no .pvd, no data set folder.
TEST(PvdWriter, OptionsFailureCommitsNothing) {
  testing::ScratchDir dir("pvd_options_fail");
  testing::write_sphere_simulation(dir.path() / "sim", 4);
  std::atomic<int> calls = 0;
  PvdSeriesOptions options;
  options.surface = [&](const MeshedStep& s, SurfacePart, const TriangleMesh*) {
    ++calls;
    if (s.step == 2) throw UserError("hook.obj", "", "disk full");
  };
  options.threads = 2;
  const fs::path out = dir.path() / "out";
  EXPECT_THROW(write_pvd_series(dir.path() / "sim", out / "melt.pvd", options), UserError);
  EXPECT_EQ(calls.load(), 7);  // every step, but step 2's outer after its inner failed
  EXPECT_TRUE(fs::is_empty(out)) << fs::directory_iterator(out)->path();
}

// Several processes (thaw run under MPI): the farm hands the steps out. Here the farm is this
// process alone (MeshFarm's own run: every item here), which takes the farm's path: each step's
// offset travels back as text, and the files are those of the series without a farm.
TEST(PvdWriter, FarmedSeriesGivesTheSameFilesAndEveryStepsOffset) {
  testing::ScratchDir dir("pvd_farm");
  const auto rows = testing::write_sphere_simulation(dir.path() / "sim", 4);
  PvdSeriesOptions options;
  options.placement = [](const MeshedStep& s, const TriangleMesh*) {
    return std::array<double, 3>{0.1 * static_cast<double>(s.step), 1.0 / 3.0, -2e-7};
  };
  const fs::path alone = dir.path() / "alone" / "melt.pvd";
  const fs::path farmed = dir.path() / "farmed" / "melt.pvd";
  const StepOffsets expected = write_pvd_series(dir.path() / "sim", alone, options);
  WorkFarm farm;
  options.farm = &farm;
  const StepOffsets offsets = write_pvd_series(dir.path() / "sim", farmed, options);
  ASSERT_EQ(offsets.size(), rows.size());
  EXPECT_EQ(offsets, expected);  // 17 digits: exactly the placement's doubles
  for (const auto& row : rows)
    EXPECT_EQ(offsets.at(row.step)[0], 0.1 * static_cast<double>(row.step));
  EXPECT_EQ(file_bytes(farmed), file_bytes(alone));
  for (const auto& e : fs::directory_iterator(alone.parent_path() / "melt_vtp"))
    EXPECT_EQ(file_bytes(farmed.parent_path() / "melt_vtp" / e.path().filename()),
              file_bytes(e.path()))
        << e.path();
}

// A process other than the leader writes its steps into the folder the leader staged (the farm
// shares that it staged, then the path), commits nothing and returns no offsets; a step failing
// travels as its outcome and is thrown as it was (a UserError with its file), committing nothing.
class FarmHere : public WorkFarm {
 public:
  /// `staged`: the leader's outcome of staging (ok: ""), then `shared`: its folder.
  FarmHere(bool leader, std::string shared, std::string staged = "")
      : m_leader(leader), m_words{std::move(staged), std::move(shared)} {}
  bool leader() const override { return m_leader; }
  std::string share(const std::string& text) override {
    return m_leader ? text : m_words[m_told++ % 2];
  }

 private:
  bool m_leader;
  std::string m_words[2];
  int m_told = 0;
};

TEST(PvdWriter, FarmedSeriesOnAnotherProcessWritesIntoTheLeadersStagedFolder) {
  testing::ScratchDir dir("pvd_farm_other");
  testing::write_sphere_simulation(dir.path() / "sim", 3);
  const fs::path pvd = dir.path() / "out" / "melt.pvd";
  const PvdWriter leaders(pvd);  // stages out/melt_vtp
  FarmHere other(false, leaders.write_dir().string());
  PvdSeriesOptions options;
  options.farm = &other;
  EXPECT_TRUE(write_pvd_series(dir.path() / "sim", pvd, options).empty());
  EXPECT_EQ(std::distance(fs::directory_iterator(leaders.write_dir()), fs::directory_iterator()),
            6);  // 3 steps x 2 surfaces
  EXPECT_FALSE(fs::exists(pvd));
  EXPECT_FALSE(fs::exists(pvd.parent_path() / "melt_vtp"));
  // The leader's word that it could not stage is every process's error.
  FarmHere refused(false, "",
                   Outcome::user("out/melt_vtp", "", "cannot create output directory").to_text());
  options.farm = &refused;
  try {
    write_pvd_series(dir.path() / "sim", pvd, options);
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_EQ(e.file(), "out/melt_vtp");  // as the leader had it
  }
}

TEST(PvdWriter, FarmedSeriesFailureIsOneUserErrorOnTheLeaderAndCommitsNothing) {
  testing::ScratchDir dir("pvd_farm_fail");
  testing::write_sphere_simulation(dir.path() / "sim", 4);
  PvdSeriesOptions options;
  options.surface = [&](const MeshedStep& s, SurfacePart, const TriangleMesh*) {
    if (s.step == 2) throw UserError("hook.obj", "", "disk full");
  };
  FarmHere leader(true, "");
  options.farm = &leader;
  const fs::path out = dir.path() / "out";
  try {
    write_pvd_series(dir.path() / "sim", out / "melt.pvd", options);
    ADD_FAILURE() << "no error";
  } catch (const UserError& e) {
    EXPECT_STREQ(e.what(), "hook.obj: disk full");
    EXPECT_EQ(e.file(), "hook.obj");  // the failure as it was, not rebuilt from its text
  }
  EXPECT_TRUE(fs::is_empty(out)) << fs::directory_iterator(out)->path();
}

TEST(PvdWriter, UnwritableOutputIsUserError) {
  testing::ScratchDir dir("pvd");
  write_file_atomic(dir.path() / "file", "x");
  // A path below a regular file cannot be created.
  EXPECT_THROW(PvdWriter(dir.path() / "file" / "x.pvd"), UserError);
  const auto rows = testing::write_sphere_simulation(dir.path() / "sim", 2);
  fs::remove(dir.path() / "sim" / "mesh" / "manifest.json");
  EXPECT_THROW(write_pvd_series(dir.path() / "sim", dir.path() / "a.pvd"), UserError);
}

}  // namespace
}  // namespace thaw::inspect
