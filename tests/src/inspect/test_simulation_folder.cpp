// Tests of src/inspect/simulation_folder: a hand-made melting-sphere folder is read and inspected
// step by step; a manifest that does not fit its interfaces.csv is a UserError.
#include "src/inspect/simulation_folder.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "base/error.h"
#include "tests/src/inspect/test_meshes.h"

namespace thaw::inspect {
namespace {

TEST(SimulationFolder, ReadsAndInspectsEveryStep) {
  testing::ScratchDir dir("sim");
  const auto rows = testing::write_sphere_simulation(dir.path(), 4);
  ASSERT_TRUE(is_simulation_folder(dir.path()));
  const SimulationFolder f = read_simulation_folder(dir.path());
  ASSERT_TRUE(f.meshed);
  ASSERT_TRUE(f.geometry.has_value());
  EXPECT_EQ(f.geometry->geometry, sim::Geometry::sphere);
  ASSERT_EQ(f.steps.size(), 4u);
  EXPECT_FALSE(f.steps[3].inner.has_value());  // the core has melted away... in this fixture
  EXPECT_EQ(f.steps[2].time_s, 180.0);

  std::int64_t last_done = 0, last_total = 0;
  const auto reports = inspect_simulation(
      f, [&](std::int64_t done, std::int64_t total) { last_done = done, last_total = total; });
  EXPECT_EQ(last_done, 4);
  EXPECT_EQ(last_total, 4);
  ASSERT_EQ(reports.size(), 4u);
  for (const StepReport& r : reports) {
    ASSERT_TRUE(r.outer.has_value());
    EXPECT_TRUE(r.outer->closed);
    EXPECT_EQ(r.outer->triangles, 1280);
    const double exact = 4.0 / 3.0 * M_PI * std::pow(r.step.outer_radius_m, 3);
    ASSERT_TRUE(r.outer_exact_volume_m3.has_value());
    EXPECT_NEAR(*r.outer_exact_volume_m3, exact, exact * 1e-14);
    // Inscribed polyhedron: below the sphere's volume. The level-3 icosphere's deficit is
    // about 1.6% (see IcosphereVolumeConvergesAtSecondOrder: error ~ C h^2, C from level 0);
    // 3% bounds it with margin while still catching a wrong radius or a wrong volume formula.
    EXPECT_LT(r.outer->volume_m3, exact);
    EXPECT_GT(r.outer->volume_m3, 0.97 * exact);
  }
  EXPECT_FALSE(reports[3].inner.has_value());

  const nlohmann::ordered_json j = to_json(reports);
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 4u);
  EXPECT_TRUE(j[3]["inner"].is_null());
  EXPECT_EQ(j[1]["time_s"], 90.0);
  EXPECT_LT(j[0]["outer"]["volume_error_rel"].get<double>(), 0.0);
  const std::string table = format_table(f, reports);
  EXPECT_NE(table.find("(vanished)"), std::string::npos);
  EXPECT_NE(table.find("geometry sphere"), std::string::npos);
}

TEST(SimulationFolder, UnmeshedFolderStillReadsRows) {
  testing::ScratchDir dir("sim");
  testing::write_sphere_simulation(dir.path(), 3);
  std::filesystem::remove_all(dir.path() / "mesh");
  const SimulationFolder f = read_simulation_folder(dir.path());
  EXPECT_FALSE(f.meshed);
  EXPECT_EQ(f.rows.size(), 3u);
  EXPECT_NE(format_table(f, {}).find("not meshed"), std::string::npos);
}

TEST(SimulationFolder, BadManifestsAreUserErrors) {
  testing::ScratchDir dir("sim");
  const auto rows = testing::write_sphere_simulation(dir.path(), 2);
  const auto manifest = dir.path() / "mesh" / "manifest.json";
  auto expect_error = [&](const std::string& text, const std::string& where) {
    write_file_atomic(manifest, text);
    try {
      read_mesh_manifest(manifest, rows);
      ADD_FAILURE() << "no error for " << text;
    } catch (const UserError& e) {
      EXPECT_EQ(e.file(), manifest.string());
      EXPECT_EQ(e.where(), where) << e.what();
    }
  };
  // A complete step record of row k (the shared manifest reader requires every key).
  auto step = [&](int k, const std::string& extra = "") {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  R"({"step":%d,"time_s":%.17g,"inner_radius_m":0.01,"outer_radius_m":0.02%s)", k,
                  rows[static_cast<std::size_t>(k)].time_s, extra.c_str());
    return std::string(buf);
  };
  const std::string head = R"({"format":"thaw-mesh/1","steps":[)";
  expect_error("{", "");
  expect_error(R"({"format":"thaw-mesh/2","steps":[]})", "format");
  expect_error(R"({"format":"thaw-mesh/1"})", "steps");
  expect_error(
      head +
          R"({"step":7,"time_s":0,"inner_radius_m":0.01,"outer_radius_m":0.02,"inner":null,"outer":null}]})",
      "steps[0].step");
  expect_error(
      head +
          R"({"step":1,"time_s":5e9,"inner_radius_m":0.01,"outer_radius_m":0.02,"inner":null,"outer":null}]})",
      "steps[0].time_s");
  expect_error(head + step(0, R"(,"inner":null})") + "]}", "steps[0].outer");
  expect_error(head + step(0, R"(,"inner":3,"outer":null})") + "]}", "steps[0].inner");
  expect_error(
      head +
          R"({"step":0,"time_s":0,"inner_radius_m":-1,"outer_radius_m":0.02,"inner":null,"outer":null}]})",
      "steps[0].inner_radius_m");
  expect_error(head + step(1, R"(,"inner":null,"outer":null})") + "," +
                   step(0, R"(,"inner":null,"outer":null})") + "]}",
               "steps[1].step");
  // A manifest naming a file that is not there fails when the step is inspected.
  write_file_atomic(manifest, head + step(0, R"(,"inner":null,"outer":"gone.obj"})") + "]}");
  EXPECT_THROW(inspect_simulation(read_simulation_folder(dir.path())), UserError);
}

TEST(SimulationFolder, ExactVolumes) {
  sim::ShellGeometry g;
  g.geometry = sim::Geometry::cylinder;
  g.length_m = 0.05;
  const double r = 0.01;
  EXPECT_DOUBLE_EQ(*exact_volume_m3(g, r), M_PI * r * r * 0.05 + 4.0 / 3.0 * M_PI * r * r * r);
  g.geometry = sim::Geometry::planar;
  EXPECT_FALSE(exact_volume_m3(g, r).has_value());
  EXPECT_FALSE(exact_volume_m3(std::nullopt, r).has_value());
}

}  // namespace
}  // namespace thaw::inspect
