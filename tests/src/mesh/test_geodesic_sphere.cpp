// Tests of src/mesh/geodesic_sphere: the mesh is a closed, 2-manifold, outward sphere with the
// counts of the class I subdivision and its vertices on the sphere; the frequency chosen is the
// least whose facets meet Mesh_3's criteria, measured on the whole mesh.
#include "src/mesh/geodesic_sphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "src/mesh/surface_mesher.h"

namespace thaw::mesh {
namespace {

using Vec = std::array<double, 3>;

double dist(const Vec& a, const Vec& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

// The worst facet of the whole mesh, measured directly: circumcentre (by its barycentric
// weights a^2 (b^2 + c^2 - a^2) ...) and its distance to the sphere, smallest angle.
GeodesicFacets measured(const TriangleMesh& m, double r) {
  GeodesicFacets g;
  for (const auto& f : m.faces) {
    const Vec &A = m.vertices[f[0]], &B = m.vertices[f[1]], &C = m.vertices[f[2]];
    const double a2 = std::pow(dist(B, C), 2), b2 = std::pow(dist(C, A), 2),
                 c2 = std::pow(dist(A, B), 2);
    const double wa = a2 * (b2 + c2 - a2), wb = b2 * (c2 + a2 - b2), wc = c2 * (a2 + b2 - c2);
    Vec o{};
    for (int k = 0; k < 3; ++k) o[k] = (wa * A[k] + wb * B[k] + wc * C[k]) / (wa + wb + wc);
    g.max_distance_m = std::max(g.max_distance_m, r - std::hypot(o[0], o[1], o[2]));
    const double a = std::sqrt(a2), b = std::sqrt(b2), c = std::sqrt(c2);
    for (const auto& [x, y, z] : {std::array{a, b, c}, std::array{b, c, a}, std::array{c, a, b}})
      g.min_angle_deg = std::min(g.min_angle_deg, std::acos((y * y + z * z - x * x) / (2 * y * z)) *
                                                      180 / std::numbers::pi);
  }
  g.max_ball_radius_m = std::sqrt(2 * r * g.max_distance_m);
  return g;
}

TEST(GeodesicSphere, ClosedOutwardSphereOfTheSubdivisionsCounts) {
  for (const int n : {1, 2, 3, 7, 18}) {
    const double r = 0.0123;
    const TriangleMesh m = geodesic_sphere(r, n);
    EXPECT_EQ(m.faces.size(), static_cast<std::size_t>(20 * n * n)) << n;
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(10 * n * n + 2)) << n;
    // Closed, 2-manifold, Euler characteristic 2, no self-intersection, outward (CGAL's checks).
    EXPECT_EQ(check_closed_manifold_outward(m), "") << n;
    // On the sphere: a normalised point times r, a few roundings (4 ulp) off.
    for (const auto& v : m.vertices) EXPECT_NEAR(std::hypot(v[0], v[1], v[2]), r, 4e-16 * r);
    EXPECT_TRUE(m.normals.empty());
  }
  EXPECT_EQ(geodesic_sphere(1, 5).vertices, geodesic_sphere(1, 5).vertices);  // deterministic
}

TEST(GeodesicSphere, FacetsOfOneFaceAreThoseOfTheWholeMesh) {
  for (const int n : {1, 4, 18}) {
    const double r = 0.03;
    const GeodesicFacets one = geodesic_facets(r, n), all = measured(geodesic_sphere(r, n), r);
    // The icosahedron's rotations carry face 0's facets onto every other face's: equal up to
    // the roundings of the two computations (relative 1e-9 of a depth ~ r n^-2 / 10).
    EXPECT_NEAR(one.max_distance_m, all.max_distance_m, 1e-9 * all.max_distance_m) << n;
    EXPECT_NEAR(one.min_angle_deg, all.min_angle_deg, 1e-9) << n;
    EXPECT_NEAR(one.max_ball_radius_m, all.max_ball_radius_m, 1e-9 * all.max_ball_radius_m);
  }
}

TEST(GeodesicSphere, FrequencyIsTheLeastMeetingTheCriteria) {
  // The default film's form: the unit sphere, distance 1e-3, angle 30, size redundant (2).
  SurfaceCriteria c{30, 2, 1e-3};
  const int n = geodesic_frequency(1, c);
  ASSERT_GT(n, 1);
  const GeodesicFacets at = geodesic_facets(1, n), below = geodesic_facets(1, n - 1);
  EXPECT_LE(at.max_distance_m, c.facet_distance_m);
  EXPECT_GT(below.max_distance_m, c.facet_distance_m);
  EXPECT_GE(at.min_angle_deg, c.facet_angle_deg);
  // Fewer triangles than Mesh_3 needs for the same bound (8408 for this form, docs/mesh.md), and
  // a volume error within the 2e-3 that Mesh_3's mesh keeps (MeshSeries tests).
  EXPECT_LT(20 * n * n, 8408);
  const double volume = enclosed_volume(geodesic_sphere(1, n));
  EXPECT_LT(1 - volume / (4 * std::numbers::pi / 3), 2e-3);
  // Scale-free: the same frequency for r and every length bound times r.
  EXPECT_EQ(geodesic_frequency(0.03, {30, 0.06, 3e-5}), n);
  // A binding size bound (ball radius <= s, i.e. distance <= s^2 / 2 on the unit sphere) asks
  // for more; an angle bound no frequency above 1 meets (55.6 degrees at n = 2, ~54 beyond)
  // gives 0 unless the icosahedron itself (60 degrees) is fine enough.
  const int sized = geodesic_frequency(1, {30, 0.02, 1e-3});
  EXPECT_GT(sized, n);
  EXPECT_LE(geodesic_facets(1, sized).max_ball_radius_m, 0.02);
  EXPECT_GT(geodesic_facets(1, sized - 1).max_ball_radius_m, 0.02);
  EXPECT_EQ(geodesic_frequency(1, {56, 2, 0.1}), 0);
  EXPECT_EQ(geodesic_frequency(1, {56, 2, 0.3}), 1);
  EXPECT_EQ(geodesic_frequency(1, {30, 2, 1e-12}), 0);  // beyond kMaxGeodesicFrequency
}

}  // namespace
}  // namespace thaw::mesh
