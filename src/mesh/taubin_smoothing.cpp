#include "src/mesh/taubin_smoothing.h"

#include <algorithm>
#include <array>
#include <vector>

namespace thaw::mesh {

namespace {
// Compressed neighbour lists: the distinct vertices sharing an edge with each vertex.
void neighbours(const TriangleMesh& m, std::vector<int>& start, std::vector<int>& list) {
  std::vector<std::vector<int>> adj(m.vertices.size());
  for (const auto& f : m.faces)
    for (int e = 0; e < 3; ++e) {
      adj[static_cast<std::size_t>(f[e])].push_back(f[(e + 1) % 3]);
      adj[static_cast<std::size_t>(f[(e + 1) % 3])].push_back(f[e]);
    }
  start.assign(m.vertices.size() + 1, 0);
  list.clear();
  for (std::size_t v = 0; v < adj.size(); ++v) {
    std::sort(adj[v].begin(), adj[v].end());
    adj[v].erase(std::unique(adj[v].begin(), adj[v].end()), adj[v].end());
    list.insert(list.end(), adj[v].begin(), adj[v].end());
    start[v + 1] = static_cast<int>(list.size());
  }
}

void step(std::vector<std::array<double, 3>>& p, const std::vector<int>& start,
          const std::vector<int>& list, double factor, std::vector<std::array<double, 3>>& next) {
  next = p;
  for (std::size_t v = 0; v < p.size(); ++v) {
    const int b = start[v], e = start[v + 1];
    if (e == b) continue;
    std::array<double, 3> mean{0, 0, 0};
    for (int k = b; k < e; ++k)
      for (int a = 0; a < 3; ++a)
        mean[a] += p[static_cast<std::size_t>(list[static_cast<std::size_t>(k)])][a];
    for (int a = 0; a < 3; ++a) next[v][a] = p[v][a] + factor * (mean[a] / (e - b) - p[v][a]);
  }
  p.swap(next);
}
}  // namespace

void taubin_smooth(TriangleMesh& mesh, const TaubinOptions& o) {
  std::vector<int> start, list;
  neighbours(mesh, start, list);
  std::vector<std::array<double, 3>> next;
  for (int pass = 0; pass < o.passes; ++pass) {
    step(mesh.vertices, start, list, o.lambda, next);
    step(mesh.vertices, start, list, o.mu, next);
  }
}

}  // namespace thaw::mesh
