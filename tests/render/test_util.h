#pragma once
// Helpers shared by the render tests: small in-memory meshes, media built in code.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <string>
#include <utility>

#include "render/geometry/triangle_mesh.h"
#include "render/scene/scene_description.h"

namespace thaw::render::test {

/// Writes a flat (not run-length encoded) Radiance RGBE file of w x h texels, texel(i, j) from
/// the top row; values whose largest component is 2^k times a multiple of 2^-8 (0.25, 0.5, 3)
/// read back exactly. Returns false if the file cannot be written.
inline bool write_flat_hdr(const std::string& path, int w, int h,
                           const std::function<RgbD(int, int)>& texel) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fprintf(f, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n", h, w);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const RgbD c = texel(i, j);
      const double v = std::max({c[0], c[1], c[2]});
      unsigned char b[4] = {0, 0, 0, 0};
      if (v > 1e-32) {
        int e = 0;
        const double m = std::frexp(v, &e), scale = m * 256.0 / v;
        for (int k = 0; k < 3; ++k) b[k] = static_cast<unsigned char>(c[k] * scale);
        b[3] = static_cast<unsigned char>(e + 128);
      }
      std::fwrite(b, 1, 4, f);
    }
  return std::fclose(f) == 0;
}

/// A medium of constant index `ior` (by field, so added members keep their defaults).
inline MediumDescription medium(const std::string& name, double ior) {
  MediumDescription m;
  m.name = name;
  m.ior = ior;
  return m;
}

/// Icosphere of `subdivisions` levels (20 * 4^s triangles), radius r, outward CCW, shared vertices.
inline TriangleMesh icosphere(int subdivisions, float r = 1.0f, Vec3 center = {0, 0, 0}) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<std::uint32_t, 3>> f = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& p : v) p = normalize(p);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalize((v[a] + v[b]) * 0.5f));
      return mid[key] = static_cast<std::uint32_t>(v.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> g;
    for (const auto& tri : f) {
      const auto a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                 c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f = std::move(g);
  }
  TriangleMesh m;
  for (auto& p : v) m.positions.push_back(center + p * r);
  m.triangles = f;
  return m;
}

}  // namespace thaw::render::test
