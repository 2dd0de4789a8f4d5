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

}  // namespace

std::uint32_t PhotonMap::bucket(int ix, int iy, int iz) const {
  // Teschner et al. 2003: xor of the coordinates times large primes.
  const auto h = (static_cast<std::uint32_t>(ix) * 73856093u) ^
                 (static_cast<std::uint32_t>(iy) * 19349663u) ^
                 (static_cast<std::uint32_t>(iz) * 83492791u);
  return h & m_mask;
}

PhotonMap::PhotonMap(std::vector<Photon> photons, float radius)
    : m_radius(radius), m_cell(2.0f * radius) {
  THAW_CHECK(radius > 0.0f && std::isfinite(radius), "photon map radius must be positive");
  if (photons.empty()) return;
  std::uint32_t buckets = 1;
  while (buckets < 2 * photons.size() && buckets < (1u << 30)) buckets <<= 1;
  m_mask = buckets - 1;
  const float inf = std::numeric_limits<float>::infinity();
  m_lo = {inf, inf, inf};
  m_hi = {-inf, -inf, -inf};
  std::vector<std::uint32_t> key(photons.size());
  m_start.assign(std::size_t(buckets) + 1, 0);
  for (std::size_t i = 0; i < photons.size(); ++i) {
    const Vec3& p = photons[i].position;
    m_lo = min(m_lo, p);
    m_hi = max(m_hi, p);
    key[i] = bucket(cell_of(p.x, m_cell), cell_of(p.y, m_cell), cell_of(p.z, m_cell));
    ++m_start[key[i] + 1];
  }
  const Vec3 r{radius, radius, radius};
  m_lo = m_lo - r;
  m_hi = m_hi + r;
  for (std::size_t k = 0; k < buckets; ++k) m_start[k + 1] += m_start[k];
  // Counting sort, stable: photons keep their order within a bucket (the result does not depend
  // on anything but the input order).
  std::vector<std::uint32_t> next(m_start.begin(), m_start.end() - 1);
  m_photons.resize(photons.size());
  for (std::size_t i = 0; i < photons.size(); ++i) m_photons[next[key[i]]++] = photons[i];
}

Rgb PhotonMap::irradiance(const Vec3& p, const Vec3& n) const {
  if (m_photons.empty()) return {};
  if (p.x < m_lo.x || p.y < m_lo.y || p.z < m_lo.z || p.x > m_hi.x || p.y > m_hi.y || p.z > m_hi.z)
    return {};
  const float r2 = m_radius * m_radius;
  // The 2 x 2 x 2 cells (each 2r wide) that the ball of radius r around p can touch.
  const int x0 = cell_of(p.x - m_radius, m_cell), y0 = cell_of(p.y - m_radius, m_cell),
            z0 = cell_of(p.z - m_radius, m_cell);
  std::uint32_t seen[8];
  int nseen = 0;
  float sum_r = 0, sum_g = 0, sum_b = 0;
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const std::uint32_t k = bucket(x0 + dx, y0 + dy, z0 + dz);
        // Two cells may share a bucket: visit it once.
        if (std::find(seen, seen + nseen, k) != seen + nseen) continue;
        seen[nseen++] = k;
        for (std::uint32_t i = m_start[k]; i < m_start[k + 1]; ++i) {
          const Photon& ph = m_photons[i];
          const Vec3 v = ph.position - p;
          const float d2 = dot(v, v);
          if (d2 >= r2) continue;
          if (dot(ph.normal, n) < kMinNormalCos ||
              std::fabs(dot(v, n)) > kMaxPlaneDistance * m_radius)
            continue;
          const float k_w = 1.0f - d2 / r2;
          sum_r += ph.power.r * k_w;
          sum_g += ph.power.g * k_w;
          sum_b += ph.power.b * k_w;
        }
      }
  const float norm = 2.0f / (kPi * r2);
  return {sum_r * norm, sum_g * norm, sum_b * norm};
}

}  // namespace thaw::render::photon
