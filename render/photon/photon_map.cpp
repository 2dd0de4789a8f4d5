// Photon density estimate; see photon_map.h.
#include "render/photon/photon_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/common/check.h"

namespace thaw::render::photon {

namespace {

constexpr float kPi = 3.14159265358979323846f;
/// Photons of another surface: normals more than acos(0.9) = 26 degrees apart, or farther than
/// r / 4 from the query's tangent plane.
constexpr float kMinNormalCos = 0.9f, kMaxPlaneDistance = 0.25f;

int cell_of(float x, float cell) {
  return static_cast<int>(std::floor(x / cell));
}

/// A photon's kernel radius over the base radius r, for n photons in the 2 x 2 x 2 grid cells
/// (2r wide) around it, whose 4 cells across a surface cover 16 r^2: a disc of radius r holds
/// about n pi / 16 of them, and a disc of radius r sqrt(K / (n pi / 16)) about K; never below 1
/// (the focused caustic keeps r), at most 8. Continuous in n, and n counted over 8 cells
/// scatters little in an evenly lit region, so the radii there stay smooth.
float radius_scale(std::uint32_t n, double photons_per_disc) {
  const double in_disc = std::max(double(n), 1.0) * (kPi / 16.0);
  return static_cast<float>(
      std::clamp(std::sqrt(photons_per_disc / in_disc), 1.0, double(PhotonMap::kMaxRadiusScale)));
}

/// Pilot density: photons hashed into cells 2r wide (Teschner et al. 2003, "Optimized spatial
/// hashing for collision detection of deformable objects"), counted per cell.
class PilotGrid {
 public:
  PilotGrid(const std::vector<Photon>& photons, float radius)
      : m_radius(radius), m_cell(2 * radius) {
    std::uint32_t buckets = 1;
    while (buckets < 2 * photons.size() && buckets < (1u << 30)) buckets <<= 1;
    m_mask = buckets - 1;
    m_count.assign(buckets, 0);
    for (const Photon& p : photons)
      ++m_count[bucket(cell_of(p.position.x, m_cell), cell_of(p.position.y, m_cell),
                       cell_of(p.position.z, m_cell))];
  }

  /// Photons in the 2 x 2 x 2 cells that a ball of radius r around p can touch.
  std::uint32_t count_near(const Vec3& p) const {
    const int x0 = cell_of(p.x - m_radius, m_cell), y0 = cell_of(p.y - m_radius, m_cell),
              z0 = cell_of(p.z - m_radius, m_cell);
    std::uint32_t seen[8];
    int nseen = 0;
    std::uint32_t n = 0;
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const std::uint32_t k = bucket(x0 + dx, y0 + dy, z0 + dz);
          // Two cells may share a bucket: count it once.
          if (std::find(seen, seen + nseen, k) != seen + nseen) continue;
          seen[nseen++] = k;
          n += m_count[k];
        }
    return n;
  }

 private:
  std::uint32_t bucket(int ix, int iy, int iz) const {
    // Teschner et al. 2003: xor of the coordinates times large primes.
    const auto h = (static_cast<std::uint32_t>(ix) * 73856093u) ^
                   (static_cast<std::uint32_t>(iy) * 19349663u) ^
                   (static_cast<std::uint32_t>(iz) * 83492791u);
    return h & m_mask;
  }

  float m_radius, m_cell;
  std::uint32_t m_mask = 0;
  std::vector<std::uint32_t> m_count;
};

}  // namespace

PhotonMap::PhotonMap(const std::vector<Photon>& photons, float radius, double photons_per_disc)
    : m_radius(radius) {
  THAW_CHECK(radius > 0.0f && std::isfinite(radius), "photon map radius must be positive");
  if (photons.empty()) return;
  THAW_CHECK(photons.size() < (1u << 31), "too many photons for one map");
  // Pilot count: the photons in the 8 grid cells around each photon, an O(1) estimate of the
  // local density (a per-photon neighbour search cost as much as the frame's queries).
  const PilotGrid pilot(photons, radius);
  m_photons.reserve(photons.size());
  for (const Photon& in : photons) {
    const float scale = radius_scale(pilot.count_near(in.position), photons_per_disc);
    Photon out = in;
    out.inv_radius2 = 1.0f / (radius * scale * radius * scale);
    m_photons.push_back(out);
  }
  m_nodes.reserve(2 * (photons.size() / kLeafPhotons + 1));
  m_nodes.emplace_back();
  build(0, 0, static_cast<std::uint32_t>(m_photons.size()));
}

void PhotonMap::build(std::uint32_t node, std::uint32_t begin, std::uint32_t end) {
  Vec3 lo = m_photons[begin].position, hi = lo, clo = lo, chi = lo;
  for (std::uint32_t i = begin; i < end; ++i) {
    const Photon& ph = m_photons[i];
    // Slightly above the kernel radius: rounding must not cut off a point with u < 1.
    const float r = 1.0001f / std::sqrt(ph.inv_radius2);
    lo = min(lo, ph.position - Vec3{r, r, r});
    hi = max(hi, ph.position + Vec3{r, r, r});
    clo = min(clo, ph.position);
    chi = max(chi, ph.position);
  }
  m_nodes[node].lo = lo;
  m_nodes[node].hi = hi;
  if (end - begin <= kLeafPhotons) {
    m_nodes[node].first = begin;
    m_nodes[node].count = end - begin;
    return;
  }
  // Median split along the widest axis of the positions (deterministic: the tree and its order
  // are a function of the input order alone).
  const Vec3 e = chi - clo;
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(
      m_photons.begin() + begin, m_photons.begin() + mid, m_photons.begin() + end,
      [axis](const Photon& a, const Photon& b) { return a.position[axis] < b.position[axis]; });
  const auto child = static_cast<std::uint32_t>(m_nodes.size());
  m_nodes[node].first = child;
  m_nodes[node].count = 0;
  m_nodes.emplace_back();
  m_nodes.emplace_back();
  build(child, begin, mid);
  build(child + 1, mid, end);
}

Rgb PhotonMap::irradiance(const Vec3& p, const Vec3& n) const {
  if (m_nodes.empty()) return {};
  float sum_r = 0, sum_g = 0, sum_b = 0;
  const auto inside = [&p](const Node& nd) {
    return p.x >= nd.lo.x && p.y >= nd.lo.y && p.z >= nd.lo.z && p.x <= nd.hi.x && p.y <= nd.hi.y &&
           p.z <= nd.hi.z;
  };
  if (!inside(m_nodes[0])) return {};
  // Depth <= log2(N / kLeafPhotons) + 1 < 32 for N < 2^31 (median splits).
  std::uint32_t stack[64];
  int top = 0;
  std::uint32_t node = 0;
  while (true) {
    const Node& nd = m_nodes[node];
    if (nd.count > 0) {
      for (std::uint32_t i = nd.first; i < nd.first + nd.count; ++i) {
        const Photon& ph = m_photons[i];
        const Vec3 v = ph.position - p;
        const float u = dot(v, v) * ph.inv_radius2;
        if (u >= 1.0f || dot(ph.normal, n) < kMinNormalCos) continue;
        const float h = dot(v, n);
        if (h * h * ph.inv_radius2 > kMaxPlaneDistance * kMaxPlaneDistance) continue;
        const float w = (1.0f - u) * ph.inv_radius2;
        sum_r += ph.power.r * w;
        sum_g += ph.power.g * w;
        sum_b += ph.power.b * w;
      }
    } else {
      const bool a = inside(m_nodes[nd.first]), b = inside(m_nodes[nd.first + 1]);
      if (a) {
        if (b) stack[top++] = nd.first + 1;
        node = nd.first;
        continue;
      }
      if (b) {
        node = nd.first + 1;
        continue;
      }
    }
    if (top == 0) break;
    node = stack[--top];
  }
  const float norm = 2.0f / kPi;
  return {sum_r * norm, sum_g * norm, sum_b * norm};
}

}  // namespace thaw::render::photon
