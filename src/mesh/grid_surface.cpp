#include "src/mesh/grid_surface.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <unordered_map>

#include "base/point3.h"

namespace thaw::mesh {

namespace {

using Vec = meshio::Point3;
using meshio::cross, meshio::dot, meshio::sub;

// Corner offsets of a lattice cube (bit 0 = x, bit 1 = y, bit 2 = z) and its Kuhn decomposition:
// the six tetrahedra 0 - e_a - e_a + e_b - 7 for the six orders (a, b, c) of the axes. Their
// edges are the 7 vectors sum of a non-empty subset of the axes, the same in every cube, so the
// tetrahedra of neighbouring cubes share faces (a conforming decomposition).
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                             {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
constexpr int kNeighbours[14][3] = {{1, 0, 0},  {-1, 0, 0},  {0, 1, 0},   {0, -1, 0},  {0, 0, 1},
                                    {0, 0, -1}, {1, 1, 0},   {-1, -1, 0}, {1, 0, 1},   {-1, 0, -1},
                                    {0, 1, 1},  {0, -1, -1}, {1, 1, 1},   {-1, -1, -1}};

// Connected non-ice regions along tetrahedron edges (14-neighbourhood); -1 for ice nodes. Region 0
// holds node (0, 0, 0), which is air (the lattice's border layer).
std::vector<int> label_regions(const NodeLattice& l, float iso, int& count) {
  const auto& n = l.nodes();
  std::vector<int> label(l.node_count(), -1);
  count = 0;
  std::deque<std::array<int, 3>> queue;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::size_t s = l.index(i, j, k);
        if (l.value(s) > iso || label[s] >= 0) continue;
        const int id = count++;
        label[s] = id;
        queue.push_back({i, j, k});
        while (!queue.empty()) {
          const auto c = queue.front();
          queue.pop_front();
          for (const auto& d : kNeighbours) {
            const int a = c[0] + d[0], b = c[1] + d[1], e = c[2] + d[2];
            if (a < 0 || b < 0 || e < 0 || a >= n[0] || b >= n[1] || e >= n[2]) continue;
            const std::size_t m = l.index(a, b, e);
            if (label[m] >= 0 || l.value(m) > iso) continue;
            label[m] = id;
            queue.push_back({a, b, e});
          }
        }
      }
  return label;
}

struct Extractor {
  const NodeLattice& lattice;
  float iso;
  const std::vector<int>& region;
  std::unordered_map<std::uint64_t, int> vertex_of_edge;
  std::vector<Vec> vertices;
  struct Tri {
    std::array<int, 3> v;
    int region;
  };
  std::vector<Tri> triangles;

  // The vertex where the isosurface crosses the lattice edge between nodes a (ice) and b.
  int crossing(std::size_t a, std::size_t b, const std::array<int, 3>& pa,
               const std::array<int, 3>& pb) {
    const std::uint64_t key =
        static_cast<std::uint64_t>(std::min(a, b)) * lattice.node_count() + std::max(a, b);
    const auto [pos, added] = vertex_of_edge.try_emplace(key, static_cast<int>(vertices.size()));
    if (added) {
      const double fa = lattice.value(a) - iso, fb = lattice.value(b) - iso;
      const double t = std::clamp(fa / (fa - fb), 1e-3, 1 - 1e-3);
      const Vec xa = lattice.position(pa[0], pa[1], pa[2]),
                xb = lattice.position(pb[0], pb[1], pb[2]);
      vertices.push_back(
          {xa[0] + t * (xb[0] - xa[0]), xa[1] + t * (xb[1] - xa[1]), xa[2] + t * (xb[2] - xa[2])});
    }
    return pos->second;
  }

  void tetrahedron(const std::array<std::array<int, 3>, 4>& p,
                   const std::array<std::size_t, 4>& node) {
    int ice_count = 0;
    std::array<bool, 4> ice{};
    for (int q = 0; q < 4; ++q) ice_count += ice[q] = lattice.value(node[q]) > iso;
    if (ice_count == 0 || ice_count == 4) return;
    std::array<int, 4> in{}, out{};
    int ni = 0, no = 0;
    for (int q = 0; q < 4; ++q) (ice[q] ? in[ni++] : out[no++]) = q;
    // The polygon's lattice edges, in cyclic order: 1 | 3 and 3 | 1 splits give a triangle
    // around the lone node, 2 | 2 a quadrilateral.
    std::array<std::array<int, 2>, 4> edges{};
    int count = 3;
    if (ni == 1 || no == 1) {
      const int lone = ni == 1 ? in[0] : out[0];
      const std::array<int, 3>& others = ni == 1 ? std::array<int, 3>{out[0], out[1], out[2]}
                                                 : std::array<int, 3>{in[0], in[1], in[2]};
      for (int e = 0; e < 3; ++e) edges[e] = {lone, others[e]};
    } else {
      count = 4;
      edges = {{{in[0], out[0]}, {in[0], out[1]}, {in[1], out[1]}, {in[1], out[0]}}};
    }
    // Orientation decided on the lattice edges' midpoints (a non-degenerate triangle or
    // parallelogram whatever the crossing positions, which only slide along the same edges):
    // the normal must point from the ice nodes to the others.
    auto mid = [&](const std::array<int, 2>& e) {
      return Vec{0.5 * (p[e[0]][0] + p[e[1]][0]), 0.5 * (p[e[0]][1] + p[e[1]][1]),
                 0.5 * (p[e[0]][2] + p[e[1]][2])};
    };
    const Vec n = cross(sub(mid(edges[1]), mid(edges[0])), sub(mid(edges[2]), mid(edges[0])));
    Vec ci{}, co{};
    for (int q = 0; q < 4; ++q)
      for (int a = 0; a < 3; ++a)
        (ice[q] ? ci : co)[a] += static_cast<double>(p[q][a]) / (ice[q] ? ni : no);
    if (dot(n, sub(co, ci)) < 0) std::reverse(edges.begin(), edges.begin() + count);
    std::array<int, 4> v{};
    for (int e = 0; e < count; ++e) {
      const auto [a, b] = edges[e];
      v[e] =
          ice[a] ? crossing(node[a], node[b], p[a], p[b]) : crossing(node[b], node[a], p[b], p[a]);
    }
    const int reg = region[node[out[0]]];  // all non-ice nodes of a tetrahedron share a region
    if (count == 3) {
      triangles.push_back({{v[0], v[1], v[2]}, reg});
      return;
    }
    // Split the quadrilateral along its shorter diagonal.
    const double d02 =
        dot(sub(vertices[v[0]], vertices[v[2]]), sub(vertices[v[0]], vertices[v[2]]));
    const double d13 =
        dot(sub(vertices[v[1]], vertices[v[3]]), sub(vertices[v[1]], vertices[v[3]]));
    if (d02 <= d13) {
      triangles.push_back({{v[0], v[1], v[2]}, reg});
      triangles.push_back({{v[0], v[2], v[3]}, reg});
    } else {
      triangles.push_back({{v[1], v[2], v[3]}, reg});
      triangles.push_back({{v[1], v[3], v[0]}, reg});
    }
  }

  void run() {
    const auto& n = lattice.nodes();
    for (int k = 0; k + 1 < n[2]; ++k)
      for (int j = 0; j + 1 < n[1]; ++j)
        for (int i = 0; i + 1 < n[0]; ++i) {
          std::array<std::array<int, 3>, 8> corner{};
          std::array<std::size_t, 8> node{};
          int ice_count = 0;
          for (int c = 0; c < 8; ++c) {
            corner[c] = {i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)};
            node[c] = lattice.index(corner[c][0], corner[c][1], corner[c][2]);
            ice_count += lattice.value(node[c]) > iso;
          }
          if (ice_count == 0 || ice_count == 8) continue;
          for (const auto& t : kTets)
            tetrahedron({corner[t[0]], corner[t[1]], corner[t[2]], corner[t[3]]},
                        {node[t[0]], node[t[1]], node[t[2]], node[t[3]]});
        }
  }
};

// The triangles of the regions selected by `keep`, compacted, optionally flipped.
template <class Keep>
TriangleMesh collect(const Extractor& x, Keep keep, bool flip) {
  TriangleMesh m;
  std::vector<int> index(x.vertices.size(), -1);
  for (const auto& t : x.triangles) {
    if (!keep(t.region)) continue;
    std::array<int, 3> f{};
    for (int c = 0; c < 3; ++c) {
      int& id = index[static_cast<std::size_t>(t.v[c])];
      if (id < 0) {
        id = static_cast<int>(m.vertices.size());
        m.vertices.push_back(x.vertices[static_cast<std::size_t>(t.v[c])]);
      }
      f[c] = id;
    }
    if (flip) std::swap(f[1], f[2]);
    m.faces.push_back(f);
  }
  return m;
}

}  // namespace

GridSurfaces extract_grid_surfaces(const NodeLattice& ice, const NodeLattice& water, float iso) {
  int regions = 0;
  const std::vector<int> region = label_regions(ice, iso, regions);
  Extractor x{ice, iso, region, {}, {}, {}};
  x.run();
  GridSurfaces s;
  s.outer = collect(
      x, [](int r) { return r == 0; }, false);
  s.inner = collect(
      x, [](int r) { return r > 0; }, true);
  s.cavities = std::max(0, regions - 1);
  double sum = 0;
  long cavity_nodes = 0;
  for (std::size_t n = 0; n < region.size(); ++n)
    if (region[n] > 0) {
      sum += water.value(n);
      ++cavity_nodes;
    }
  s.cavity_water_fraction = cavity_nodes > 0 ? sum / static_cast<double>(cavity_nodes) : 0.0;
  return s;
}

}  // namespace thaw::mesh
