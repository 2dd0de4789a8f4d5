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

/// Radius of grid c over the base radius: 2^(c/2).
float class_scale(int c) {
  return std::exp2(0.5f * float(c));
}

/// A photon's kernel radius over the base radius r, for n photons in the 2 x 2 x 2 grid cells
/// (2r wide) around it, whose 4 cells across a surface cover 16 r^2: a disc of radius r holds
/// about n pi / 16 of them, and a disc of radius r sqrt(K / (n pi / 16)) about K; never below 1
/// (the focused caustic keeps r), at most 8. Continuous in n, and n counted over 8 cells
/// scatters little in an evenly lit region, so the radii there stay smooth.
float radius_scale(std::uint32_t n, double photons_per_disc) {
  const double in_disc = std::max(double(n), 1.0) * (kPi / 16.0);
  return static_cast<float>(std::clamp(std::sqrt(photons_per_disc / in_disc), 1.0, 8.0));
}

/// The grid a photon of radius scale s goes to: the smallest c with 2^(c/2) >= s (radii in
/// steps of sqrt 2, so a query examines few photons beyond each kernel).
int radius_class(float scale) {
  int c = 0;
  while (c + 1 < PhotonMap::kClasses && class_scale(c) < scale) ++c;
  return c;
}

}  // namespace

std::uint32_t PhotonMap::Grid::bucket(int ix, int iy, int iz) const {
  // Teschner et al. 2003: xor of the coordinates times large primes.
  const auto h = (static_cast<std::uint32_t>(ix) * 73856093u) ^
                 (static_cast<std::uint32_t>(iy) * 19349663u) ^
                 (static_cast<std::uint32_t>(iz) * 83492791u);
  return h & mask;
}

PhotonMap::Grid::Grid(std::vector<Photon> in, float r) : radius(r), cell(2.0f * r) {
  if (in.empty()) return;
  std::uint32_t buckets = 1;
  while (buckets < 2 * in.size() && buckets < (1u << 30)) buckets <<= 1;
  mask = buckets - 1;
  const float inf = std::numeric_limits<float>::infinity();
  lo = {inf, inf, inf};
  hi = {-inf, -inf, -inf};
  std::vector<std::uint32_t> key(in.size());
  start.assign(std::size_t(buckets) + 1, 0);
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Vec3& p = in[i].position;
    lo = min(lo, p);
    hi = max(hi, p);
    key[i] = bucket(cell_of(p.x, cell), cell_of(p.y, cell), cell_of(p.z, cell));
    ++start[key[i] + 1];
  }
  lo = lo - Vec3{r, r, r};
  hi = hi + Vec3{r, r, r};
  for (std::size_t k = 0; k < buckets; ++k) start[k + 1] += start[k];
  // Counting sort, stable: photons keep their input order within a bucket.
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
  photons.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) photons[next[key[i]]++] = in[i];
}

template <class F>
void PhotonMap::Grid::for_each_near(const Vec3& p, F&& f) const {
  if (photons.empty()) return;
  if (p.x < lo.x || p.y < lo.y || p.z < lo.z || p.x > hi.x || p.y > hi.y || p.z > hi.z) return;
  const float r2 = radius * radius;
  // The 2 x 2 x 2 cells (each 2r wide) that the ball of radius r around p can touch.
  const int x0 = cell_of(p.x - radius, cell), y0 = cell_of(p.y - radius, cell),
            z0 = cell_of(p.z - radius, cell);
  std::uint32_t seen[8];
  int nseen = 0;
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const std::uint32_t k = bucket(x0 + dx, y0 + dy, z0 + dz);
        // Two cells may share a bucket: visit it once.
        if (std::find(seen, seen + nseen, k) != seen + nseen) continue;
        seen[nseen++] = k;
        for (std::uint32_t i = start[k]; i < start[k + 1]; ++i) {
          const Vec3 v = photons[i].position - p;
          const float d2 = dot(v, v);
          if (d2 < r2 && !f(photons[i], v, d2)) return;
        }
      }
}

std::uint32_t PhotonMap::Grid::count_near(const Vec3& p) const {
  const int x0 = cell_of(p.x - radius, cell), y0 = cell_of(p.y - radius, cell),
            z0 = cell_of(p.z - radius, cell);
  std::uint32_t seen[8];
  int nseen = 0;
  std::uint32_t n = 0;
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const std::uint32_t k = bucket(x0 + dx, y0 + dy, z0 + dz);
        if (std::find(seen, seen + nseen, k) != seen + nseen) continue;
        seen[nseen++] = k;
        n += start[k + 1] - start[k];
      }
  return n;
}

PhotonMap::PhotonMap(const std::vector<Photon>& photons, float radius, double photons_per_disc)
    : m_radius(radius) {
  THAW_CHECK(radius > 0.0f && std::isfinite(radius), "photon map radius must be positive");
  if (photons.empty()) return;
  // Pilot count: the photons in the 8 grid cells around each photon (those a query at its
  // position visits), an O(1) estimate of the local density (a per-photon neighbour search cost
  // as much as the frame's queries). Photons keep their input order per grid.
  const Grid all(photons, radius);
  std::vector<std::vector<Photon>> split(kClasses);
  for (const Photon& in : photons) {
    const std::uint32_t n = all.count_near(in.position);
    const float scale = radius_scale(n, photons_per_disc);
    Photon out = in;
    out.inv_radius2 = 1.0f / (radius * scale * radius * scale);
    split[std::size_t(radius_class(scale))].push_back(out);
  }
  for (int c = 0; c < kClasses; ++c)
    m_grids.emplace_back(std::move(split[std::size_t(c)]), radius * class_scale(c));
}

std::size_t PhotonMap::size() const {
  std::size_t n = 0;
  for (const Grid& g : m_grids) n += g.photons.size();
  return n;
}

Rgb PhotonMap::irradiance(const Vec3& p, const Vec3& n) const {
  float sum_r = 0, sum_g = 0, sum_b = 0;
  for (const Grid& g : m_grids) {
    // The grid's radius bounds its photons' own radii; each photon uses its own.
    g.for_each_near(p, [&](const Photon& ph, const Vec3& v, float d2) {
      const float u = d2 * ph.inv_radius2;
      if (u >= 1.0f || dot(ph.normal, n) < kMinNormalCos) return true;
      const float h = dot(v, n);
      if (h * h * ph.inv_radius2 > kMaxPlaneDistance * kMaxPlaneDistance) return true;
      const float w = (1.0f - u) * ph.inv_radius2;
      sum_r += ph.power.r * w;
      sum_g += ph.power.g * w;
      sum_b += ph.power.b * w;
      return true;
    });
  }
  const float norm = 2.0f / kPi;
  return {sum_r * norm, sum_g * norm, sum_b * norm};
}

}  // namespace thaw::render::photon
