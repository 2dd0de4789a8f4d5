// Tests of mesh_grid_field (src/mesh/grid_mesher.h) on GridFields sampled from analytic shapes
// (grid_field_samples.h): closed outward surfaces, their classification (outer; inner around a
// sealed cavity; one surface once the cavity opens), topology, edge length, and volume / area
// against the exact values.
//
// Tolerances, derived in docs/mesh.md ("Surfaces from grid fields"):
//  - volume: along a planar interface the 1/2 crossing of the linearly interpolated volume
//    fraction lies within delta = max over alpha in [1/2, 1] of (alpha - 1/2)(1 - alpha)/alpha
//    h = (3/2 - sqrt 2) h = 0.0858 h of the true interface (alpha = the partial cell's fraction);
//    Taubin smoothing conserves volume to first order, so |dV| <= delta A, plus, along a sharp
//    convex or concave edge of length L, at most one cell cross-section h^2 L (the 1/2 level cuts
//    across the corner cell);
//  - area of smooth surfaces: a surface within delta of one of mean curvature 1/R_min or less
//    differs in area by at most 2 delta / R_min relative (first-order offset formula).
#include "src/mesh/grid_mesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "src/mesh/surface_remesher.h"
#include "tests/src/mesh/grid_field_samples.h"

namespace thaw::mesh {
namespace {

using namespace thaw::mesh::testing;
constexpr double kPi = std::numbers::pi;
const double kDelta = 1.5 - std::sqrt(2.0);  // planar crossing error / h

double mean_edge(const TriangleMesh& m) {
  double sum = 0;
  for (const auto& f : m.faces)
    for (int e = 0; e < 3; ++e) {
      const auto &a = m.vertices[f[e]], &b = m.vertices[f[(e + 1) % 3]];
      sum += std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    }
  return sum / (3.0 * m.faces.size());
}

long euler_characteristic(const TriangleMesh& m) {
  // Closed triangle surface: E = 3F / 2.
  return static_cast<long>(m.vertices.size()) - 3 * static_cast<long>(m.faces.size()) / 2 +
         static_cast<long>(m.faces.size());
}

double radius_range(const TriangleMesh& m, bool largest) {
  double r = largest ? 0 : 1e300;
  for (const auto& v : m.vertices)
    r = largest ? std::max(r, std::hypot(v[0], v[1], v[2]))
                : std::min(r, std::hypot(v[0], v[1], v[2]));
  return r;
}

TEST(GridMesher, SphereShellInCartesianGrid) {
  const double R = 0.01, r = 0.006, h = 0.0005;
  const auto f = sample_cartesian(
      [&](double x, double y, double z) { return std::hypot(x, y, z) - R; },
      [&](double x, double y, double z) { return std::hypot(x, y, z) - r; }, 0.012, h);
  const GridMeshResult m = mesh_grid_field(f, {});
  ASSERT_EQ(check_closed_oriented_components(m.outer), "");
  ASSERT_EQ(check_closed_oriented_components(m.inner), "");
  EXPECT_EQ(m.remesh_problem, "");
  EXPECT_EQ(m.cavities, 1);
  EXPECT_GT(m.cavity_water_fraction, 0.9);  // the cavity's nodes hold water (border nodes partly)
  EXPECT_EQ(euler_characteristic(m.outer), 2);
  EXPECT_EQ(euler_characteristic(m.inner), 2);
  EXPECT_LT(radius_range(m.inner, true), radius_range(m.outer, false));  // inner strictly inside
  for (const auto& [mesh, rad] : {std::pair{&m.outer, R}, std::pair{&m.inner, r}}) {
    const double v = 4.0 / 3 * kPi * rad * rad * rad, a = 4 * kPi * rad * rad;
    EXPECT_NEAR(enclosed_volume(*mesh), v, kDelta * h * a) << rad;
    EXPECT_NEAR(surface_area(*mesh), a, 2 * kDelta * h / rad * a) << rad;
    // CGAL's remeshing keeps edges in [4/5, 4/3] of the target (the cell edge by default).
    EXPECT_GT(mean_edge(*mesh), 0.8 * h);
    EXPECT_LT(mean_edge(*mesh), 4.0 / 3 * h);
  }
  ASSERT_EQ(m.outer.normals.size(), m.outer.vertices.size());
  for (std::size_t i = 0; i < m.outer.vertices.size(); i += 97) {  // outward: along the position
    const auto &p = m.outer.vertices[i], &n = m.outer.normals[i];
    EXPECT_GT((p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / std::hypot(p[0], p[1], p[2]), 0.95);
  }
  for (std::size_t i = 0; i < m.inner.vertices.size();
       i += 97) {  // out of the cavity: also outward
    const auto &p = m.inner.vertices[i], &n = m.inner.normals[i];
    EXPECT_GT((p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / std::hypot(p[0], p[1], p[2]), 0.95);
  }
}

TEST(GridMesher, RoundedBoxWithSharpBoxCavity) {
  const double a = 0.01, e = 0.003, c = 0.006, h = 0.0005;
  const auto f = sample_cartesian(
      [&](double x, double y, double z) { return rounded_box(x, y, z, a, a, a, e); },
      [&](double x, double y, double z) { return rounded_box(x, y, z, c, c, c, 0.0); }, 0.012, h);
  const GridMeshResult m = mesh_grid_field(f, {});
  ASSERT_EQ(check_closed_oriented_components(m.outer), "");
  ASSERT_EQ(check_closed_oriented_components(m.inner), "");
  EXPECT_EQ(m.cavities, 1);
  // Rounded box = inner box of side s dilated by e (Steiner formula).
  const double s = 2 * (a - e);
  const double v = s * s * s + 6 * s * s * e + 3 * kPi * s * e * e + 4.0 / 3 * kPi * e * e * e;
  const double area = 6 * s * s + 6 * kPi * s * e + 4 * kPi * e * e;
  EXPECT_NEAR(enclosed_volume(m.outer), v, kDelta * h * area);
  EXPECT_NEAR(surface_area(m.outer), area, 2 * kDelta * h / e * area);
  // The sharp cube cavity: 12 edges of length 2c.
  const double vc = 8 * c * c * c, ac = 24 * c * c, edges = 12 * 2 * c;
  EXPECT_NEAR(enclosed_volume(m.inner), vc, kDelta * h * ac + h * h * edges);
}

TEST(GridMesher, BoredCylinderRevolvedFromAxisymmetricField) {
  // A vertical cylinder R = 1 cm, H = 1.6 cm with a 4 mm bore along the axis: one surface of
  // genus 1 (Euler characteristic 0), no cavity.
  const double R = 0.01, r = 0.004, H = 0.016, h = 0.0005;
  const auto f = sample_axisymmetric(
      [&](double rr, double y) {
        return std::max({rr - R, r - rr, std::abs(y) - H / 2});
      },
      nullptr, 0.012, 0.01, h);
  const GridMeshResult m = mesh_grid_field(f, {});
  ASSERT_EQ(check_closed_oriented_components(m.outer), "");
  EXPECT_EQ(m.cavities, 0);
  EXPECT_TRUE(m.inner.faces.empty());
  EXPECT_EQ(euler_characteristic(m.outer), 0);
  const double v = kPi * (R * R - r * r) * H,
               area = 2 * kPi * (R + r) * H + 2 * kPi * (R * R - r * r);
  const double edges = 2 * 2 * kPi * (R + r);
  EXPECT_NEAR(enclosed_volume(m.outer), v, kDelta * h * area + h * h * edges);
}

TEST(GridMesher, SphereShellRevolvedFromAxisymmetricField) {
  const double R = 0.01, r = 0.006, h = 0.0005;
  const auto f = sample_axisymmetric([&](double rr, double y) { return std::hypot(rr, y) - R; },
                                     [&](double rr, double y) { return std::hypot(rr, y) - r; },
                                     0.012, 0.012, h);
  const GridMeshResult m = mesh_grid_field(f, {});
  ASSERT_EQ(check_closed_oriented_components(m.outer), "");
  ASSERT_EQ(check_closed_oriented_components(m.inner), "");
  EXPECT_EQ(m.cavities, 1);
  // The revolved field is the ring-averaged fraction interpolated bilinearly in (r, y): the same
  // planar crossing bound holds (the interpolation is linear along any lattice edge's direction
  // to first order in h / R).
  for (const auto& [mesh, rad] : {std::pair{&m.outer, R}, std::pair{&m.inner, r}}) {
    const double v = 4.0 / 3 * kPi * rad * rad * rad, a = 4 * kPi * rad * rad;
    EXPECT_NEAR(enclosed_volume(*mesh), v, kDelta * h * a) << rad;
  }
}

TEST(GridMesher, CavityOpenToTheOutsideGivesOneSurface) {
  // A cube with a box cavity that reaches through its top face (the shell after break-through).
  const double a = 0.01, c = 0.006, h = 0.0005;
  const auto f = sample_cartesian(
      [&](double x, double y, double z) { return rounded_box(x, y, z, a, a, a, 0.0); },
      [&](double x, double y, double z) { return rounded_box(x, y - 0.005, z, c, c, c, 0.0); },
      0.012, h);
  const GridMeshResult m = mesh_grid_field(f, {});
  EXPECT_EQ(m.cavities, 0);
  EXPECT_TRUE(m.inner.faces.empty());
  ASSERT_EQ(check_closed_oriented_components(m.outer), "");
  EXPECT_EQ(euler_characteristic(m.outer), 2);  // a cup: one surface of genus 0
  // Cube minus the part of the cavity inside it (y from -1 mm to the top at 10 mm).
  const double v = 8 * a * a * a - (2 * c) * (2 * c) * (a - (0.005 - c));
  const double area =
      24 * a * a + 4 * (2 * c) * 0.011;  // outside + the pit's walls and floor, minus its mouth
  const double edges = 12 * 2 * a + 4 * 2 * c * 2 + 4 * 0.011;
  EXPECT_NEAR(enclosed_volume(m.outer), v, kDelta * h * area + h * h * edges);
}

double field_volume(const sim::GridField& f, const std::vector<float>& fraction) {
  double v = 0;
  for (int k = 0; k < f.cells[2]; ++k)
    for (int j = 0; j < f.cells[1]; ++j)
      for (int i = 0; i < f.cells[0]; ++i) v += fraction[f.index(i, j, k)] * cell_volume_m3(f, i);
  return v;
}

TEST(GridMesher, BlockAverageKeepsVolumesAndMeshesCoarseEdgesWithinTheCoarseBound) {
  const double R = 0.01, r = 0.006, h = 0.0005;
  const auto f = sample_cartesian(
      [&](double x, double y, double z) { return std::hypot(x, y, z) - R; },
      [&](double x, double y, double z) { return std::hypot(x, y, z) - r; }, 0.0121, h);
  // Fractions are stored as float: each coarse value is rounded by at most 2^-24 relative, so the
  // sums agree to 2^-24 of the total.
  const sim::GridField c = coarsened_twice(f);  // 49 cells -> 25: the last block half outside
  EXPECT_EQ(c.cells[0], (f.cells[0] + 1) / 2);
  EXPECT_NEAR(field_volume(c, c.ice_fraction), field_volume(f, f.ice_fraction),
              0x1p-24 * field_volume(f, f.ice_fraction));
  EXPECT_NEAR(field_volume(c, c.water_fraction), field_volume(f, f.water_fraction),
              0x1p-24 * field_volume(f, f.water_fraction));
  const auto a = sample_axisymmetric([&](double rr, double y) { return std::hypot(rr, y) - R; },
                                     nullptr, 0.0121, 0.012, h);
  const sim::GridField ac = coarsened_twice(a);  // rings weighted by their volume
  EXPECT_NEAR(field_volume(ac, ac.ice_fraction), field_volume(a, a.ice_fraction),
              0x1p-24 * field_volume(a, a.ice_fraction));
  // Edges of 2 h: meshed from the block average, within the bound at cell edge 2 h.
  GridMeshOptions o;
  o.edge_length_m = 2 * h;
  const GridMeshResult m = mesh_grid_field(f, o);
  ASSERT_EQ(check_closed_oriented_components(m.outer), "");
  EXPECT_EQ(m.cavities, 1);
  const double v = 4.0 / 3 * kPi * R * R * R, area = 4 * kPi * R * R;
  EXPECT_NEAR(enclosed_volume(m.outer), v, kDelta * 2 * h * area);
}

// A water-filled box cavity in an ice box whose +x wall has thinned to one layer of cells that
// are `wall_ice` ice (the rest melt water, held by the cavity: sim/grid/cavity_drain.h). The
// solver counts the cavity as sealed while that layer holds any ice (at 60 % the 2 x 2 x 2 block
// average pairs the layer with the cavity's water, 0.3 ice, so a mesh from the block average
// would open the shell before the solver's break_through; at 40 % the solver's former rule, a
// path of cells less than half ice, had opened it). `drained`: the layer is gone and the
// cavity's water has drained, as the solver writes the step it opens.
sim::GridField thin_walled_box(float wall_ice, bool drained = false) {
  sim::GridField f;
  f.geometry = sim::GridField::Geometry::cartesian3d;
  const int n = 20;
  f.cells = {n, n, n};
  f.spacing_m = 0.0005;
  f.origin_m = {-0.005, -0.005, -0.005};
  f.temperature_c.assign(f.cell_count(), 0.0f);
  f.ice_fraction.assign(f.cell_count(), 0.0f);
  f.water_fraction.assign(f.cell_count(), 0.0f);
  auto in = [](int i, int lo, int hi) { return i >= lo && i <= hi; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = f.index(i, j, k);
        if (!in(i, 3, 15) || !in(j, 3, 16) || !in(k, 3, 16)) continue;  // air
        const bool cavity = in(i, 5, 14) && in(j, 5, 14) && in(k, 5, 14);
        const float ice = cavity ? 0.0f : (i == 15 ? wall_ice : 1.0f);
        f.ice_fraction[c] = ice;
        f.water_fraction[c] = drained && (cavity || i == 15) ? 0.0f : 1.0f - ice;
      }
  return f;
}

TEST(GridMesher, CavityStaysSealedUntilTheSolverOpensIt) {
  GridMeshOptions o;
  o.edge_length_m = 0.001;  // two cells: the block average would be used
  for (const float wall_ice : {0.6f, 0.4f}) {
    const GridMeshResult sealed = mesh_grid_field(thin_walled_box(wall_ice), o);
    EXPECT_EQ(sealed.cavities, 1) << wall_ice;
    EXPECT_GT(sealed.cavity_water_fraction, 0.9) << wall_ice;
    ASSERT_EQ(check_closed_oriented_components(sealed.outer), "");
    ASSERT_EQ(check_closed_oriented_components(sealed.inner), "");
  }
  const GridMeshResult open = mesh_grid_field(thin_walled_box(0.0f, true), o);
  EXPECT_EQ(open.cavities, 0);
  EXPECT_TRUE(open.inner.faces.empty());
}

TEST(GridMesher, NoIceGivesNoSurface) {
  const auto f =
      sample_cartesian([](double, double, double) { return 1.0; }, nullptr, 0.004, 0.0005);
  const GridMeshResult m = mesh_grid_field(f, {});
  EXPECT_TRUE(m.outer.faces.empty());
  EXPECT_TRUE(m.inner.faces.empty());
}

// The mesher's own guard (issue 27): a field outside sim::find_header_problem's bounds is an
// internal error naming the header field, never a SIGFPE, SIGSEGV or an endless allocation.
// read_grid_field refuses such files as the user's error before they get here.
TEST(GridMesherDeathTest, FieldOutsideTheBoundsIsAnInternalCheck) {
  auto f = sample_cartesian([](double, double, double) { return 1.0; }, nullptr, 0.004, 0.0005);
  f.spacing_m = 1e300;
  EXPECT_DEATH(mesh_grid_field(f, {}), "spacing_m");
  f.spacing_m = 0.0005;
  f.origin_m[1] = 1e308;
  EXPECT_DEATH(mesh_grid_field(f, {}), "origin_m");
}

}  // namespace
}  // namespace thaw::mesh
