#pragma once
// The regular icosahedron and its subdivisions projected onto a sphere: a closed, outward,
// 2-manifold surface with every vertex exactly at distance R, whose volume and area are known in
// closed form at level 0 and converge at second order to the sphere's. Used by the inspector's
// tests and benchmark. Header-only, no test framework.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "src/inspect/triangle_mesh.h"

namespace thaw::inspect::testing {

/// Regular icosahedron with circumradius `radius` centred at `center`, faces counter-clockwise
/// seen from outside; each of `levels` subdivisions splits every triangle into four and pushes
/// the new vertices out to the sphere. 20 * 4^levels triangles.
inline TriangleMesh icosphere(double radius, int levels, std::array<double, 3> center = {0, 0, 0}) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<std::array<double, 3>> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::int64_t, 3>> f = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
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
    mesh.vertices.push_back(
        {center[0] + radius * p[0], center[1] + radius * p[1], center[2] + radius * p[2]});
  mesh.triangles = f;
  return mesh;
}

}  // namespace thaw::inspect::testing
