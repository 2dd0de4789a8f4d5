#pragma once
// Meshes with known answers for the inspector's tests, built in code: the regular icosahedron and
// its subdivisions projected onto a sphere (all vertices exactly at distance R), plus a scratch
// folder helper and a simulation-folder fixture (interfaces.csv + mesh/manifest.json + OBJs).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <unistd.h>
#include <utility>

#include "sim/io/interface_history.h"
#include "src/common/atomic_file.h"
#include "src/inspect/obj_reader.h"
#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect::testing {

/// Regular icosahedron with circumradius `radius` centred at `center`, faces counter-clockwise
/// seen from outside; each of `levels` subdivisions splits every triangle into four and pushes
/// the new vertices out to the sphere. 20 * 4^levels triangles.
inline TriangleMesh icosphere(double radius, int levels, std::array<double, 3> center = {0, 0, 0}) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> v = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                                          {0, -1, t}, {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                                          {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::int64_t, 3>> f = {
      {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  auto unit = [](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] / n, p[1] / n, p[2] / n};
  };
  for (auto& p : v) p = unit(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::int64_t, std::int64_t>, std::int64_t> mid;
    auto midpoint = [&](std::int64_t a, std::int64_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(unit({v[a][0] + v[b][0], v[a][1] + v[b][1], v[a][2] + v[b][2]}));
      const auto id = static_cast<std::int64_t>(v.size() - 1);
      mid[key] = id;
      return id;
    };
    std::vector<std::array<std::int64_t, 3>> next;
    for (const auto& tri : f) {
      const std::int64_t a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                         c = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    f = std::move(next);
  }
  TriangleMesh mesh;
  for (const auto& p : v)
    mesh.vertices.push_back({center[0] + radius * p[0], center[1] + radius * p[1],
                             center[2] + radius * p[2]});
  mesh.triangles = f;
  return mesh;
}

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
      write_obj(dir / "mesh" / name, icosphere(r.inner_radius_m, 3));
      inner = std::string("\"") + name + "\"";
    }
    std::snprintf(name, sizeof name, "step_%06d_outer.obj", k);
    write_obj(dir / "mesh" / name, icosphere(r.outer_radius_m, 3));
    outer = std::string("\"") + name + "\"";
    char entry[512];
    std::snprintf(entry, sizeof entry,
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
