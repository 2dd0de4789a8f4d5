#pragma once
// Helpers for the inspector's tests: icospheres (icosphere.h), a scratch folder, and a
// simulation-folder fixture (interfaces.csv + summary.json + mesh/manifest.json + OBJs).
#include <gtest/gtest.h>

#include <unistd.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "base/atomic_file.h"
#include "base/obj_writer.h"
#include "sim/format/interface_history.h"
#include "src/inspect/triangle_mesh.h"
#include "tests/src/inspect/icosphere.h"

namespace thaw::inspect::testing {

/// A fresh empty folder under the build tree, removed at the end of the test.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_path = std::filesystem::path(THAW_BINARY_DIR) / "test-scratch" /
             (name + "-" + info->name() + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(m_path);
    std::filesystem::create_directories(m_path);
  }
  ~ScratchDir() {
    std::error_code ec;
    if (!::testing::Test::HasFailure()) std::filesystem::remove_all(m_path, ec);
  }
  const std::filesystem::path& path() const { return m_path; }

 private:
  std::filesystem::path m_path;
};

/// A melting-sphere simulation folder: `steps` rows with the inner radius shrinking from 10 mm to
/// 0 (vanished at the last step) and the outer from 15 mm to 12 mm, icosphere meshes (level 3)
/// for every surface that exists, interfaces.csv, summary.json (sphere) and mesh/manifest.json.
inline std::vector<sim::InterfaceRecord> write_sphere_simulation(const std::filesystem::path& dir,
                                                                 int steps = 4) {
  std::filesystem::create_directories(dir / "mesh");
  std::vector<sim::InterfaceRecord> rows;
  std::string manifest = R"({"format":"thaw-mesh/1","options":{"levels":3},"steps":[)";
  for (int k = 0; k < steps; ++k) {
    sim::InterfaceRecord r;
    r.step = k;
    r.time_s = 90.0 * k;  // 0, 90 s, 180 s, ...
    const double f = steps > 1 ? static_cast<double>(k) / (steps - 1) : 0.0;
    r.inner_radius_m = k + 1 == steps && steps > 1 ? 0.0 : 0.010 * (1.0 - f);
    r.outer_radius_m = 0.015 - 0.003 * f;
    r.liquid_volume_m3 = 4.0 / 3.0 * M_PI * std::pow(r.inner_radius_m, 3);
    r.ice_volume_m3 = 4.0 / 3.0 * M_PI * std::pow(r.outer_radius_m, 3) - r.liquid_volume_m3;
    rows.push_back(r);
    char name[64];
    std::string inner = "null", outer;
    if (r.inner_radius_m > 0) {
      std::snprintf(name, sizeof name, "step_%06d_inner.obj", k);
      meshio::write_obj(dir / "mesh" / name, icosphere(r.inner_radius_m, 3));
      inner = std::string("\"") + name + "\"";
    }
    std::snprintf(name, sizeof name, "step_%06d_outer.obj", k);
    meshio::write_obj(dir / "mesh" / name, icosphere(r.outer_radius_m, 3));
    outer = std::string("\"") + name + "\"";
    char entry[512];
    std::snprintf(
        entry, sizeof entry,
        R"(%s{"step":%d,"time_s":%.17g,"inner_radius_m":%.17g,"outer_radius_m":%.17g,"inner":%s,"outer":%s,"triangles":1280})",
        k == 0 ? "" : ",", k, r.time_s, r.inner_radius_m, r.outer_radius_m, inner.c_str(),
        outer.c_str());
    manifest += entry;
  }
  manifest += "]}\n";
  sim::write_interfaces_csv(dir / "interfaces.csv", rows);
  write_file_atomic(dir / "summary.json",
                    R"({"parameters":{"simulation":{"geometry":"sphere"},"shell":{}}})");
  write_file_atomic(dir / "mesh" / "manifest.json", manifest);
  return rows;
}

}  // namespace thaw::inspect::testing
