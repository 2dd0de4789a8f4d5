// Tests of the option handling (src/mesh/mesh_options.h): validation, the triangle budget and
// the triangle target (no CGAL: fast).
#include "src/mesh/mesh_options.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "base/error.h"

namespace thaw::mesh {
namespace {

ShellShape make(sim::Geometry g, double r, double half) {
  ShellShape s;
  s.geometry = g;
  s.radius_m = r;
  s.core_half_size_m = half;
  return s;
}

TEST(MeshOptions, ValidateRejectsOutOfRange) {
  EXPECT_NO_THROW(validate(MeshOptions{}));
  auto rejects = [](auto change) {
    MeshOptions o;
    change(o);
    EXPECT_THROW(validate(o), UserError);
  };
  rejects([](MeshOptions& o) { o.angle_deg = 45; });
  rejects([](MeshOptions& o) { o.edge_length_m = -1; });
  rejects([](MeshOptions& o) { o.distance_m = std::numeric_limits<double>::quiet_NaN(); });
  rejects([](MeshOptions& o) { o.triangles = 10; });
  rejects([](MeshOptions& o) { o.jobs = -2; });
  rejects([](MeshOptions& o) { o.relative_error_bound = 0.1; });
}

// Found by the bad-input sweep (tests/src/cli/bad_input_sweep.sh): --edge-length 1e-6 on a
// 1.5 cm shell (about 5e9 triangles) ran for minutes (the budget relaxes only the distance bound),
// and edge_length_m = 1e-300 was reported against render.shell.center by thaw run.
TEST(MeshOptions, AnEdgeOrDistanceAskingForTooManyTrianglesIsRefused) {
  MeshOptions tiny_edge;
  tiny_edge.edge_length_m = 1e-300;
  try {
    validate(tiny_edge);
    ADD_FAILURE() << "1e-300 accepted";
  } catch (const UserError& e) {
    EXPECT_EQ(e.where(), "edge_length_m");
    EXPECT_EQ(e.problem(), "must be 0 (automatic) or at least 1e-06 m, got 1e-300");
  }
  const ShellShape ball = make(sim::Geometry::sphere, 0.015, 0);
  auto refused_key = [&](const MeshOptions& o) -> std::string {
    try {
      check_triangle_count(ball, criteria_for(ball, o));
    } catch (const UserError& e) {
      return e.where();
    }
    return "";
  };
  MeshOptions edge;
  edge.edge_length_m = 1e-6;  // 1.32 A / (e / sqrt 3)^2 = 1.1e10 triangles
  EXPECT_EQ(refused_key(edge), "edge_length_m");
  MeshOptions distance;
  distance.max_triangles = 0;  // no budget to relax it
  distance.distance_m = 1e-12;
  EXPECT_EQ(refused_key(distance), "distance_m");
  // The defaults, and an edge giving about 1e6 triangles, pass.
  EXPECT_EQ(refused_key(MeshOptions{}), "");
  MeshOptions fine;
  fine.edge_length_m = 1e-4;
  EXPECT_EQ(refused_key(fine), "");
}

TEST(MeshOptions, DefaultCriteriaOfA3cmSphere) {
  const SurfaceCriteria c = criteria_for(make(sim::Geometry::sphere, 0.03, 0), MeshOptions{});
  EXPECT_DOUBLE_EQ(c.facet_distance_m, 3e-5);
  EXPECT_DOUBLE_EQ(c.facet_size_m, 2.5e-3 / std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(c.facet_angle_deg, 30);
  // The relative bound takes over for a small core.
  EXPECT_DOUBLE_EQ(
      criteria_for(make(sim::Geometry::sphere, 0.002, 0), MeshOptions{}).facet_distance_m, 2e-6);
}

TEST(MeshOptions, BudgetRelaxesTheDistanceOfAThinCapsule) {
  // A 0.1 mm needle 10 cm long would need ~3e6 triangles at distance 1e-7 m.
  const ShellShape needle = make(sim::Geometry::cylinder, 1e-4, 0.05);
  const MeshOptions o;
  const SurfaceCriteria c = criteria_for(needle, o);
  EXPECT_GT(c.facet_distance_m, 1e-7);
  EXPECT_LE(estimate_triangles(needle, c), static_cast<double>(o.max_triangles));
  MeshOptions unlimited;
  unlimited.max_triangles = 0;
  EXPECT_DOUBLE_EQ(criteria_for(needle, unlimited).facet_distance_m, 1e-7);
}

TEST(MeshOptions, ThinSlabIsTooThinToMesh) {
  const MeshOptions o;
  EXPECT_TRUE(too_thin_to_mesh(make(sim::Geometry::planar, 1e-5, 0.02), o));
  EXPECT_FALSE(too_thin_to_mesh(make(sim::Geometry::planar, 5e-3, 0.02), o));
  EXPECT_FALSE(too_thin_to_mesh(make(sim::Geometry::sphere, 1e-5, 0), o));
}

TEST(MeshOptions, TriangleTargetSetsEdgeAndRelaxesDistance) {
  MeshOptions o;
  o.triangles = 10000;
  const double area = 4 * 3.14159265358979 * 0.03 * 0.03;
  const MeshOptions r = resolve_triangle_target(o, area);
  EXPECT_NEAR(r.edge_length_m, std::sqrt(3 * 1.32 * area / 10000), 1e-15);
  EXPECT_TRUE(r.distance_relaxed);
  o.keep_distance = true;
  EXPECT_DOUBLE_EQ(resolve_triangle_target(o, area).distance_m, MeshOptions{}.distance_m);
}

}  // namespace
}  // namespace thaw::mesh
