#include "base/edge_topology.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>

namespace thaw::meshio {
namespace {

/// One undirected edge (lo < hi) and how the triangles use it.
struct EdgeSlot {
  std::int64_t lo = -1, hi = -1;  // lo == -1: empty slot
  std::int32_t uses = 0;
  std::int32_t direction_sum = 0;  // +1 per traversal lo -> hi, -1 per hi -> lo
};

/// Open addressing with linear probing, at most half full: O(1) expected per edge.
class EdgeTable {
 public:
  explicit EdgeTable(std::size_t max_edges)
      : m_slots(std::bit_ceil(std::max<std::size_t>(16, 2 * max_edges))),
        m_mask(m_slots.size() - 1) {}

  void add(std::int64_t a, std::int64_t b) {
    const std::int64_t lo = std::min(a, b), hi = std::max(a, b);
    std::size_t i = hash(lo, hi) & m_mask;
    while (m_slots[i].lo != -1 && (m_slots[i].lo != lo || m_slots[i].hi != hi))
      i = (i + 1) & m_mask;
    EdgeSlot& s = m_slots[i];
    s.lo = lo;
    s.hi = hi;
    ++s.uses;
    s.direction_sum += a < b ? 1 : -1;
  }
  const std::vector<EdgeSlot>& slots() const { return m_slots; }

 private:
  static std::size_t hash(std::int64_t lo, std::int64_t hi) {
    // splitmix64 finaliser of the pair: spreads consecutive indices over the whole table.
    std::uint64_t x =
        static_cast<std::uint64_t>(lo) * 0x9e3779b97f4a7c15ULL ^ static_cast<std::uint64_t>(hi);
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return static_cast<std::size_t>(x);
  }
  std::vector<EdgeSlot> m_slots;
  std::size_t m_mask;
};

std::int64_t find_root(std::vector<std::int64_t>& parent, std::int64_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];  // path halving
    i = parent[i];
  }
  return i;
}

}  // namespace

EdgeTopology edge_topology(const std::vector<std::array<double, 3>>& vertices,
                           const std::vector<std::array<std::int64_t, 3>>& triangles) {
  EdgeTopology r;
  const std::size_t nv = vertices.size();
  EdgeTable table(3 * triangles.size());
  std::vector<std::int64_t> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<char> used(nv, 0);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::int64_t a = t[k], b = t[(k + 1) % 3];
      table.add(a, b);
      used[a] = 1;
      const std::int64_t ra = find_root(parent, a), rb = find_root(parent, b);
      if (ra != rb) parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  double sum = 0;
  r.min_edge_m = std::numeric_limits<double>::infinity();
  for (const EdgeSlot& s : table.slots()) {
    if (s.lo == -1) continue;
    ++r.edges;
    if (s.uses == 1) ++r.boundary_edges;
    if (s.uses >= 3) ++r.non_manifold_edges;
    // Two triangles agreeing in orientation traverse their shared edge in opposite directions.
    if (s.uses == 2 && s.direction_sum != 0) ++r.inconsistent_edges;
    const auto& p = vertices[s.lo];
    const auto& q = vertices[s.hi];
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
    sum += len;
    r.min_edge_m = std::min(r.min_edge_m, len);
    r.max_edge_m = std::max(r.max_edge_m, len);
  }
  r.mean_edge_m = r.edges > 0 ? sum / static_cast<double>(r.edges) : 0;
  if (r.edges == 0) r.min_edge_m = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!used[v]) continue;
    ++r.used_vertices;
    if (find_root(parent, static_cast<std::int64_t>(v)) == static_cast<std::int64_t>(v))
      ++r.components;
  }
  return r;
}

}  // namespace thaw::meshio
