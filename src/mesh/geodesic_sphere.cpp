#include "src/mesh/geodesic_sphere.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>

#include "base/check.h"

namespace thaw::mesh {

namespace {

using Vec = std::array<double, 3>;

// The regular icosahedron: its 12 vertices (0, +-1, +-phi) cyclically, on the unit sphere, and
// its 20 faces counter-clockwise seen from outside.
const std::array<Vec, 12>& icosahedron_vertices() {
  static const std::array<Vec, 12> v = [] {
    constexpr double p = std::numbers::phi;
    std::array<Vec, 12> u = {{{-1, p, 0},
                              {1, p, 0},
                              {-1, -p, 0},
                              {1, -p, 0},
                              {0, -1, p},
                              {0, 1, p},
                              {0, -1, -p},
                              {0, 1, -p},
                              {p, 0, -1},
                              {p, 0, 1},
                              {-p, 0, -1},
                              {-p, 0, 1}}};
    for (Vec& x : u) {
      const double n = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
      for (double& c : x) c /= n;
    }
    return u;
  }();
  return v;
}

constexpr std::array<std::array<int, 3>, 20> kFaces = {
    {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
     {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
     {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}}};

// Grid point (i, j) of face f at frequency n (barycentric weights n - i - j, i, j on the face's
// corners), projected onto the unit sphere.
Vec grid_point(int f, int n, int i, int j) {
  const auto& v = icosahedron_vertices();
  const auto& [a, b, c] = kFaces[static_cast<std::size_t>(f)];
  Vec p{};
  for (int k = 0; k < 3; ++k) p[k] = (v[a][k] * (n - i - j) + v[b][k] * i + v[c][k] * j) / n;
  const double len = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
  for (double& x : p) x /= len;
  return p;
}

// Each sub-triangle of face f at frequency n as grid coordinates, counter-clockwise like the
// face: (i, j), (i+1, j), (i, j+1) and, except on the far edge, (i+1, j), (i+1, j+1), (i, j+1).
template <class Visit>
void for_each_triangle(int n, Visit&& visit) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n - i; ++j) {
      visit(std::array<std::array<int, 2>, 3>{{{i, j}, {i + 1, j}, {i, j + 1}}});
      if (i + j < n - 1)
        visit(std::array<std::array<int, 2>, 3>{{{i + 1, j}, {i + 1, j + 1}, {i, j + 1}}});
    }
}

double distance(const Vec& a, const Vec& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

bool meets(const GeodesicFacets& g, const SurfaceCriteria& c) {
  return g.min_angle_deg >= c.facet_angle_deg && g.max_ball_radius_m <= c.facet_size_m &&
         g.max_distance_m <= c.facet_distance_m;
}

}  // namespace

GeodesicFacets geodesic_facets(double radius_m, int n) {
  THAW_CHECK(n >= 1 && n <= kMaxGeodesicFrequency, "geodesic frequency in range");
  GeodesicFacets g;
  double max_depth = 0;  // on the unit sphere
  for_each_triangle(n, [&](const std::array<std::array<int, 2>, 3>& t) {
    const Vec p[3] = {grid_point(0, n, t[0][0], t[0][1]), grid_point(0, n, t[1][0], t[1][1]),
                      grid_point(0, n, t[2][0], t[2][1])};
    const double a = distance(p[1], p[2]), b = distance(p[2], p[0]), c = distance(p[0], p[1]);
    // Circumradius R = abc / (4 area), area by Heron in its stable form (Kahan).
    std::array<double, 3> s = {a, b, c};
    std::sort(s.begin(), s.end(), std::greater<>());
    const double area4 = std::sqrt((s[0] + (s[1] + s[2])) * (s[2] - (s[0] - s[1])) *
                                   (s[2] + (s[0] - s[1])) * (s[0] + (s[1] - s[2])));
    const double r2 = std::pow(a * b * c / area4, 2);
    // 1 - sqrt(1 - R^2) without cancellation.
    max_depth = std::max(max_depth, r2 / (1 + std::sqrt(std::max(0.0, 1 - r2))));
    // Smallest angle: opposite the shortest side (law of cosines).
    const double cos_min = (s[0] * s[0] + s[1] * s[1] - s[2] * s[2]) / (2 * s[0] * s[1]);
    g.min_angle_deg = std::min(g.min_angle_deg,
                               std::acos(std::clamp(cos_min, -1.0, 1.0)) * 180 / std::numbers::pi);
  });
  g.max_distance_m = radius_m * max_depth;
  g.max_ball_radius_m = radius_m * std::sqrt(2 * max_depth);
  return g;
}

int geodesic_frequency(double radius_m, const SurfaceCriteria& criteria) {
  // The facets shrink as 1/n (their depth as 1/n^2): bounds no frequency up to the largest can
  // meet are told from n = 64 without measuring the large ones (a step costs n^2 facets).
  const GeodesicFacets g64 = geodesic_facets(radius_m, 64);
  const double needed = 64 * std::max(std::sqrt(g64.max_distance_m / criteria.facet_distance_m),
                                      g64.max_ball_radius_m / criteria.facet_size_m);
  if (!(needed <= 1.1 * kMaxGeodesicFrequency)) return 0;
  // A frequency that meets the criteria by doubling, then the least one by bisection. Past twice
  // the frequency the lengths need, only the angle can fail, and it does not improve with n
  // (60 degrees at n = 1, 55.6 at 2, falling towards 54.0).
  const int limit = static_cast<int>(std::min<double>(kMaxGeodesicFrequency, 2 * needed + 2));
  int lo = 0, hi = 1;  // lo fails (0: none tried)
  while (!meets(geodesic_facets(radius_m, hi), criteria)) {
    if (hi >= limit) return 0;
    lo = hi;
    hi = std::min(2 * hi, limit);
  }
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (meets(geodesic_facets(radius_m, mid), criteria) ? hi : lo) = mid;
  }
  return hi;
}

TriangleMesh geodesic_sphere(double radius_m, int n) {
  THAW_CHECK(n >= 1 && n <= kMaxGeodesicFrequency, "geodesic frequency in range");
  THAW_CHECK(radius_m > 0 && std::isfinite(radius_m), "sphere radius finite and > 0");
  TriangleMesh m;
  m.vertices.reserve(static_cast<std::size_t>(10) * n * n + 2);
  m.faces.reserve(static_cast<std::size_t>(20) * n * n);
  // A grid point on a face's edge or corner is shared with the neighbouring faces: it is named by
  // its nonzero (corner, weight) pairs, sorted, and made once (by the first face that needs it).
  std::map<std::array<int, 6>, int> index;
  for (int f = 0; f < 20; ++f) {
    const auto& corner = kFaces[static_cast<std::size_t>(f)];
    auto vertex = [&](int i, int j) {
      std::array<std::pair<int, int>, 3> w = {
          {{corner[0], n - i - j}, {corner[1], i}, {corner[2], j}}};
      std::sort(w.begin(), w.end());
      std::array<int, 6> key{-1, 0, -1, 0, -1, 0};
      int k = 0;
      for (const auto& [id, weight] : w)
        if (weight > 0) key[2 * k] = id, key[2 * k + 1] = weight, ++k;
      const auto [pos, added] = index.try_emplace(key, static_cast<int>(m.vertices.size()));
      if (added) {
        Vec p = grid_point(f, n, i, j);
        for (double& x : p) x *= radius_m;
        m.vertices.push_back(p);
      }
      return pos->second;
    };
    for_each_triangle(n, [&](const std::array<std::array<int, 2>, 3>& t) {
      m.faces.push_back(
          {vertex(t[0][0], t[0][1]), vertex(t[1][0], t[1][1]), vertex(t[2][0], t[2][1])});
    });
  }
  return m;
}

}  // namespace thaw::mesh
