// Photon density estimate; see photon_map.h.
#include "render/photon/photon_map.h"

#include <algorithm>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "base/check.h"

namespace thaw::render::photon {

namespace {

constexpr float kPi = 3.14159265358979323846f;
/// Photons of another surface: normals more than acos(0.9) = 26 degrees apart, or farther than
/// r / 4 from the query's tangent plane.
constexpr float kMinNormalCos = 0.9f, kMaxPlaneDistance = 0.25f;
/// A subtree counts as lying on the query's surface only if its bound on (h / r)^2 is below
/// the plane test's limit by this factor: far beyond the float rounding of the per-photon h
/// (a few ulps of the photon's distance, < 1e-6 r), so that test would pass for every photon.
constexpr float kSurfaceMargin = 0.999f;
/// Relative bound on the rounding of the subtree's plane-distance bound (a sum of six products
/// in float: < 8 ulps of the sum of their magnitudes).
constexpr float kRoundingBound = 1e-6f;

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

/// Photons in the left half of a node of n > kLeafPhotons photons: about n / 2, a multiple of
/// kLeafPhotons (at least one block, and fewer than n).
std::uint32_t full_leaves_split(std::uint32_t n) {
  const std::uint32_t k = PhotonMap::kLeafPhotons;
  return std::max(k, (n / 2 + k / 2) / k * k);
}

}  // namespace

PhotonMap::PhotonMap(const std::vector<Photon>& photons, float radius, double photons_per_disc)
    : m_radius(radius) {
  THAW_CHECK(radius > 0.0f && std::isfinite(radius), "photon map radius must be positive");
  if (photons.empty()) return;
  THAW_CHECK(photons.size() < (1u << 30), "too many photons for one map");
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
  std::vector<Node> nodes;
  nodes.reserve(2 * (photons.size() / kLeafPhotons + 1));
  nodes.emplace_back();
  build(nodes, 0, 0, static_cast<std::uint32_t>(m_photons.size()));
  m_wide.emplace_back();
  if (nodes[0].count > 0) {  // a single leaf: a root with one child
    WideNode& root = m_wide[0];
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < kWidth; ++i) {
        root.lo[a][i] = std::numeric_limits<float>::infinity();
        root.hi[a][i] = -std::numeric_limits<float>::infinity();
      }
    root.lo[0][0] = nodes[0].lo.x;
    root.lo[1][0] = nodes[0].lo.y;
    root.lo[2][0] = nodes[0].lo.z;
    root.hi[0][0] = nodes[0].hi.x;
    root.hi[1][0] = nodes[0].hi.y;
    root.hi[2][0] = nodes[0].hi.z;
    const std::uint32_t block = add_block(nodes[0]);
    m_wide[0].child[0] = block;
    m_wide[0].leaf_mask = 1;
  } else {
    collapse(nodes, 0, 0);
  }
}

void PhotonMap::build(std::vector<Node>& nodes, std::uint32_t node, std::uint32_t begin,
                      std::uint32_t end) {
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
  nodes[node].lo = lo;
  nodes[node].hi = hi;
  nodes[node].begin = begin;
  nodes[node].end = end;
  if (end - begin <= kLeafPhotons) {
    nodes[node].first = begin;
    nodes[node].count = end - begin;
    return;
  }
  // Split along the widest axis of the positions at the median rounded to a multiple of
  // kLeafPhotons, so that every leaf but the last is a full block (deterministic:
  // the tree and its order are a function of the input order alone). Halves at the plain median
  // left a quarter of the blocks' lanes empty on the default film: 27 % slower lookups.
  const Vec3 e = chi - clo;
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  const std::uint32_t mid = begin + full_leaves_split(end - begin);
  std::nth_element(
      m_photons.begin() + begin, m_photons.begin() + mid, m_photons.begin() + end,
      [axis](const Photon& a, const Photon& b) { return a.position[axis] < b.position[axis]; });
  const auto child = static_cast<std::uint32_t>(nodes.size());
  nodes[node].first = child;
  nodes[node].count = 0;
  nodes.emplace_back();
  nodes.emplace_back();
  build(nodes, child, begin, mid);
  build(nodes, child + 1, mid, end);
}

std::uint32_t PhotonMap::add_block(const Node& leaf) {
  PhotonBlock b{};
  for (std::uint32_t k = 0; k < leaf.count; ++k) {
    const Photon& ph = m_photons[leaf.first + k];
    b.x[k] = ph.position.x;
    b.y[k] = ph.position.y;
    b.z[k] = ph.position.z;
    b.nx[k] = ph.normal.x;
    b.ny[k] = ph.normal.y;
    b.nz[k] = ph.normal.z;
    b.inv_r2[k] = ph.inv_radius2;
    b.r[k] = ph.power.r;
    b.g[k] = ph.power.g;
    b.b[k] = ph.power.b;
  }
  m_blocks.push_back(b);
  return static_cast<std::uint32_t>(m_blocks.size() - 1);
}

void PhotonMap::describe(const Node& node, WideNode& w, int i) const {
  const Photon& first = m_photons[node.begin];
  Vec3 lo = first.position, hi = lo;
  float max_inv = 0;
  bool one_normal = true;
  for (std::uint32_t k = node.begin; k < node.end; ++k) {
    const Photon& ph = m_photons[k];
    lo = min(lo, ph.position);
    hi = max(hi, ph.position);
    max_inv = std::max(max_inv, ph.inv_radius2);
    one_normal = one_normal && ph.normal.x == first.normal.x && ph.normal.y == first.normal.y &&
                 ph.normal.z == first.normal.z;
  }
  for (int a = 0; a < 3; ++a) {
    w.pos_lo[a][i] = lo[a];
    w.pos_hi[a][i] = hi[a];
    w.normal[a][i] = one_normal ? first.normal[a] : 0.0f;
  }
  w.max_inv_r2[i] = max_inv;
  if (one_normal) w.one_normal |= 1u << i;
}

void PhotonMap::collapse(const std::vector<Node>& nodes, std::uint32_t node, std::uint32_t wide) {
  // The node's children, and interior ones opened level by level into theirs: up to kWidth
  // slots, in the binary tree's left-to-right order.
  std::uint32_t slots[kWidth] = {nodes[node].first, nodes[node].first + 1};
  int n = 2;
  for (bool opened = true; opened && n < kWidth;) {
    opened = false;
    for (int i = 0; i < n && n < kWidth; ++i) {
      if (nodes[slots[i]].count > 0) continue;
      const std::uint32_t first = nodes[slots[i]].first;
      for (int j = n; j > i + 1; --j) slots[j] = slots[j - 1];
      slots[i] = first;
      slots[i + 1] = first + 1;
      ++n;
      ++i;  // the new right child stays for the next level
      opened = true;
    }
  }
  WideNode w{};
  for (int i = 0; i < kWidth; ++i) {
    const bool used = i < n;
    const Vec3 lo =
        used ? nodes[slots[i]].lo : Vec3{1, 1, 1} * std::numeric_limits<float>::infinity();
    const Vec3 hi =
        used ? nodes[slots[i]].hi : Vec3{1, 1, 1} * -std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
      w.lo[a][i] = lo[a];
      w.hi[a][i] = hi[a];
    }
    if (used) describe(nodes[slots[i]], w, i);
  }
  m_wide[wide] = w;
  for (int i = 0; i < n; ++i) {
    const Node& c = nodes[slots[i]];
    if (c.count > 0) {
      const std::uint32_t block = add_block(c);
      m_wide[wide].child[i] = block;
      m_wide[wide].leaf_mask |= 1u << i;
    } else {
      const auto child = static_cast<std::uint32_t>(m_wide.size());
      m_wide.emplace_back();
      m_wide[wide].child[i] = child;
      collapse(nodes, slots[i], child);
    }
  }
}

#if defined(__SSE2__)
namespace {
/// Lanes 0..7 of a channel's per-lane sums added in one fixed order (both kernels).
float lane_total(const float s[8]) {
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}
}  // namespace

/// The lookup's tests for 8 lanes (a node's children, a leaf's photons), SSE: two halves of 4,
/// each lane summed on its own.
struct PhotonMap::LookupSse {
  __m128 px, py, pz, qx, qy, qz, aqx, aqy, aqz;
  __m128 sum_r[2], sum_g[2], sum_b[2];

  LookupSse(const Vec3& p, const Vec3& n)
      : px(_mm_set1_ps(p.x)),
        py(_mm_set1_ps(p.y)),
        pz(_mm_set1_ps(p.z)),
        qx(_mm_set1_ps(n.x)),
        qy(_mm_set1_ps(n.y)),
        qz(_mm_set1_ps(n.z)),
        aqx(_mm_set1_ps(std::fabs(n.x))),
        aqy(_mm_set1_ps(std::fabs(n.y))),
        aqz(_mm_set1_ps(std::fabs(n.z))) {
    for (int h = 0; h < 2; ++h) sum_r[h] = sum_g[h] = sum_b[h] = _mm_setzero_ps();
  }

  /// The children whose boxes contain p.
  unsigned inside(const WideNode& w) const {
    unsigned mask = 0;
    for (int o = 0; o < kWidth; o += 4) {
      const __m128 in =
          _mm_and_ps(_mm_and_ps(_mm_and_ps(_mm_cmple_ps(_mm_load_ps(w.lo[0] + o), px),
                                           _mm_cmple_ps(px, _mm_load_ps(w.hi[0] + o))),
                                _mm_and_ps(_mm_cmple_ps(_mm_load_ps(w.lo[1] + o), py),
                                           _mm_cmple_ps(py, _mm_load_ps(w.hi[1] + o)))),
                     _mm_and_ps(_mm_cmple_ps(_mm_load_ps(w.lo[2] + o), pz),
                                _mm_cmple_ps(pz, _mm_load_ps(w.hi[2] + o))));
      mask |= static_cast<unsigned>(_mm_movemask_ps(in)) << o;
    }
    return mask;
  }

  /// The children whose subtrees lie on the query's surface: their common normal passes the
  /// normal test (the per-photon expression, so the same float value), and the box of their
  /// positions lies within r_min / 4 of the tangent plane: |(c - p).n| + half extents projected
  /// on n, plus a bound on that sum's rounding, with the margin kSurfaceMargin.
  unsigned on_surface(const WideNode& w) const {
    const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 half = _mm_set1_ps(0.5f), rounding = _mm_set1_ps(kRoundingBound),
                 surface_h2 = _mm_set1_ps(kMaxPlaneDistance * kMaxPlaneDistance * kSurfaceMargin),
                 min_cos = _mm_set1_ps(kMinNormalCos);
    unsigned mask = 0;
    for (int o = 0; o < kWidth; o += 4) {
      const __m128 lox = _mm_load_ps(w.pos_lo[0] + o), hix = _mm_load_ps(w.pos_hi[0] + o);
      const __m128 loy = _mm_load_ps(w.pos_lo[1] + o), hiy = _mm_load_ps(w.pos_hi[1] + o);
      const __m128 loz = _mm_load_ps(w.pos_lo[2] + o), hiz = _mm_load_ps(w.pos_hi[2] + o);
      const __m128 cos_n = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(w.normal[0] + o), qx),
                                                 _mm_mul_ps(_mm_load_ps(w.normal[1] + o), qy)),
                                      _mm_mul_ps(_mm_load_ps(w.normal[2] + o), qz));
      const __m128 dx = _mm_mul_ps(_mm_sub_ps(_mm_mul_ps(_mm_add_ps(lox, hix), half), px), qx);
      const __m128 dy = _mm_mul_ps(_mm_sub_ps(_mm_mul_ps(_mm_add_ps(loy, hiy), half), py), qy);
      const __m128 dz = _mm_mul_ps(_mm_sub_ps(_mm_mul_ps(_mm_add_ps(loz, hiz), half), pz), qz);
      const __m128 extent =
          _mm_mul_ps(half, _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_sub_ps(hix, lox), aqx),
                                                 _mm_mul_ps(_mm_sub_ps(hiy, loy), aqy)),
                                      _mm_mul_ps(_mm_sub_ps(hiz, loz), aqz)));
      const __m128 terms =
          _mm_add_ps(_mm_add_ps(_mm_and_ps(dx, abs_mask), _mm_and_ps(dy, abs_mask)),
                     _mm_add_ps(_mm_and_ps(dz, abs_mask), extent));
      const __m128 hb =
          _mm_add_ps(_mm_add_ps(_mm_and_ps(_mm_add_ps(_mm_add_ps(dx, dy), dz), abs_mask), extent),
                     _mm_mul_ps(terms, rounding));
      const __m128 ok = _mm_and_ps(
          _mm_cmpge_ps(cos_n, min_cos),
          _mm_cmple_ps(_mm_mul_ps(_mm_mul_ps(hb, hb), _mm_load_ps(w.max_inv_r2 + o)), surface_h2));
      mask |= static_cast<unsigned>(_mm_movemask_ps(ok)) << o;
    }
    return mask & w.one_normal;
  }

  /// Adds the block's photons that count at p; with `flat` the normal and plane tests are known
  /// to pass (see photon_map.h).
  void add(const PhotonBlock& b, bool flat) {
    const __m128 one = _mm_set1_ps(1.0f), min_cos = _mm_set1_ps(kMinNormalCos),
                 max_h2 = _mm_set1_ps(kMaxPlaneDistance * kMaxPlaneDistance);
    for (int h = 0; h < 2; ++h) {
      const int o = 4 * h;
      const __m128 vx = _mm_sub_ps(_mm_load_ps(b.x + o), px),
                   vy = _mm_sub_ps(_mm_load_ps(b.y + o), py),
                   vz = _mm_sub_ps(_mm_load_ps(b.z + o), pz);
      const __m128 inv = _mm_load_ps(b.inv_r2 + o);
      const __m128 u = _mm_mul_ps(
          _mm_add_ps(_mm_add_ps(_mm_mul_ps(vx, vx), _mm_mul_ps(vy, vy)), _mm_mul_ps(vz, vz)), inv);
      __m128 ok = _mm_cmplt_ps(u, one);
      if (!flat) {
        const __m128 cos_n = _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_load_ps(b.nx + o), qx),
                                                   _mm_mul_ps(_mm_load_ps(b.ny + o), qy)),
                                        _mm_mul_ps(_mm_load_ps(b.nz + o), qz));
        const __m128 hq =
            _mm_add_ps(_mm_add_ps(_mm_mul_ps(vx, qx), _mm_mul_ps(vy, qy)), _mm_mul_ps(vz, qz));
        ok = _mm_and_ps(_mm_and_ps(ok, _mm_cmpge_ps(cos_n, min_cos)),
                        _mm_cmple_ps(_mm_mul_ps(_mm_mul_ps(hq, hq), inv), max_h2));
      }
      const __m128 wgt = _mm_and_ps(_mm_mul_ps(_mm_sub_ps(one, u), inv), ok);
      sum_r[h] = _mm_add_ps(sum_r[h], _mm_mul_ps(wgt, _mm_load_ps(b.r + o)));
      sum_g[h] = _mm_add_ps(sum_g[h], _mm_mul_ps(wgt, _mm_load_ps(b.g + o)));
      sum_b[h] = _mm_add_ps(sum_b[h], _mm_mul_ps(wgt, _mm_load_ps(b.b + o)));
    }
  }

  Rgb total() const {
    alignas(32) float r[8], g[8], b[8];
    for (int h = 0; h < 2; ++h) {
      _mm_store_ps(r + 4 * h, sum_r[h]);
      _mm_store_ps(g + 4 * h, sum_g[h]);
      _mm_store_ps(b + 4 * h, sum_b[h]);
    }
    return {lane_total(r), lane_total(g), lane_total(b)};
  }
};

#if THAW_AVX2_DISPATCH
/// LookupSse's tests on all 8 lanes at once: the same operations lane for lane (no FMA: the
/// same rounding), so the same masks and sums.
struct PhotonMap::LookupAvx2 {
  __m256 px, py, pz, qx, qy, qz, aqx, aqy, aqz;
  __m256 sum_r, sum_g, sum_b;

  THAW_TARGET_AVX2 LookupAvx2(const Vec3& p, const Vec3& n)
      : px(_mm256_set1_ps(p.x)),
        py(_mm256_set1_ps(p.y)),
        pz(_mm256_set1_ps(p.z)),
        qx(_mm256_set1_ps(n.x)),
        qy(_mm256_set1_ps(n.y)),
        qz(_mm256_set1_ps(n.z)),
        aqx(_mm256_set1_ps(std::fabs(n.x))),
        aqy(_mm256_set1_ps(std::fabs(n.y))),
        aqz(_mm256_set1_ps(std::fabs(n.z))),
        sum_r(_mm256_setzero_ps()),
        sum_g(_mm256_setzero_ps()),
        sum_b(_mm256_setzero_ps()) {}

  THAW_TARGET_AVX2 unsigned inside(const WideNode& w) const {
    const __m256 in = _mm256_and_ps(
        _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(_mm256_load_ps(w.lo[0]), px, _CMP_LE_OQ),
                                    _mm256_cmp_ps(px, _mm256_load_ps(w.hi[0]), _CMP_LE_OQ)),
                      _mm256_and_ps(_mm256_cmp_ps(_mm256_load_ps(w.lo[1]), py, _CMP_LE_OQ),
                                    _mm256_cmp_ps(py, _mm256_load_ps(w.hi[1]), _CMP_LE_OQ))),
        _mm256_and_ps(_mm256_cmp_ps(_mm256_load_ps(w.lo[2]), pz, _CMP_LE_OQ),
                      _mm256_cmp_ps(pz, _mm256_load_ps(w.hi[2]), _CMP_LE_OQ)));
    return static_cast<unsigned>(_mm256_movemask_ps(in));
  }

  THAW_TARGET_AVX2 unsigned on_surface(const WideNode& w) const {
    const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
    const __m256 half = _mm256_set1_ps(0.5f), rounding = _mm256_set1_ps(kRoundingBound),
                 surface_h2 =
                     _mm256_set1_ps(kMaxPlaneDistance * kMaxPlaneDistance * kSurfaceMargin),
                 min_cos = _mm256_set1_ps(kMinNormalCos);
    const __m256 lox = _mm256_load_ps(w.pos_lo[0]), hix = _mm256_load_ps(w.pos_hi[0]);
    const __m256 loy = _mm256_load_ps(w.pos_lo[1]), hiy = _mm256_load_ps(w.pos_hi[1]);
    const __m256 loz = _mm256_load_ps(w.pos_lo[2]), hiz = _mm256_load_ps(w.pos_hi[2]);
    const __m256 cos_n =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_load_ps(w.normal[0]), qx),
                                    _mm256_mul_ps(_mm256_load_ps(w.normal[1]), qy)),
                      _mm256_mul_ps(_mm256_load_ps(w.normal[2]), qz));
    const __m256 dx =
        _mm256_mul_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(lox, hix), half), px), qx);
    const __m256 dy =
        _mm256_mul_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(loy, hiy), half), py), qy);
    const __m256 dz =
        _mm256_mul_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(loz, hiz), half), pz), qz);
    const __m256 extent = _mm256_mul_ps(
        half, _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_sub_ps(hix, lox), aqx),
                                          _mm256_mul_ps(_mm256_sub_ps(hiy, loy), aqy)),
                            _mm256_mul_ps(_mm256_sub_ps(hiz, loz), aqz)));
    const __m256 terms =
        _mm256_add_ps(_mm256_add_ps(_mm256_and_ps(dx, abs_mask), _mm256_and_ps(dy, abs_mask)),
                      _mm256_add_ps(_mm256_and_ps(dz, abs_mask), extent));
    const __m256 hb = _mm256_add_ps(
        _mm256_add_ps(_mm256_and_ps(_mm256_add_ps(_mm256_add_ps(dx, dy), dz), abs_mask), extent),
        _mm256_mul_ps(terms, rounding));
    const __m256 ok = _mm256_and_ps(
        _mm256_cmp_ps(cos_n, min_cos, _CMP_GE_OQ),
        _mm256_cmp_ps(_mm256_mul_ps(_mm256_mul_ps(hb, hb), _mm256_load_ps(w.max_inv_r2)),
                      surface_h2, _CMP_LE_OQ));
    return static_cast<unsigned>(_mm256_movemask_ps(ok)) & w.one_normal;
  }

  THAW_TARGET_AVX2 void add(const PhotonBlock& b, bool flat) {
    const __m256 one = _mm256_set1_ps(1.0f), min_cos = _mm256_set1_ps(kMinNormalCos),
                 max_h2 = _mm256_set1_ps(kMaxPlaneDistance * kMaxPlaneDistance);
    const __m256 vx = _mm256_sub_ps(_mm256_load_ps(b.x), px),
                 vy = _mm256_sub_ps(_mm256_load_ps(b.y), py),
                 vz = _mm256_sub_ps(_mm256_load_ps(b.z), pz);
    const __m256 inv = _mm256_load_ps(b.inv_r2);
    const __m256 u =
        _mm256_mul_ps(_mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, vx), _mm256_mul_ps(vy, vy)),
                                    _mm256_mul_ps(vz, vz)),
                      inv);
    __m256 ok = _mm256_cmp_ps(u, one, _CMP_LT_OQ);
    if (!flat) {
      const __m256 cos_n = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(_mm256_load_ps(b.nx), qx),
                                                       _mm256_mul_ps(_mm256_load_ps(b.ny), qy)),
                                         _mm256_mul_ps(_mm256_load_ps(b.nz), qz));
      const __m256 hq = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, qx), _mm256_mul_ps(vy, qy)),
                                      _mm256_mul_ps(vz, qz));
      ok = _mm256_and_ps(
          _mm256_and_ps(ok, _mm256_cmp_ps(cos_n, min_cos, _CMP_GE_OQ)),
          _mm256_cmp_ps(_mm256_mul_ps(_mm256_mul_ps(hq, hq), inv), max_h2, _CMP_LE_OQ));
    }
    const __m256 wgt = _mm256_and_ps(_mm256_mul_ps(_mm256_sub_ps(one, u), inv), ok);
    sum_r = _mm256_add_ps(sum_r, _mm256_mul_ps(wgt, _mm256_load_ps(b.r)));
    sum_g = _mm256_add_ps(sum_g, _mm256_mul_ps(wgt, _mm256_load_ps(b.g)));
    sum_b = _mm256_add_ps(sum_b, _mm256_mul_ps(wgt, _mm256_load_ps(b.b)));
  }

  THAW_TARGET_AVX2 Rgb total() const {
    alignas(32) float r[8], g[8], b[8];
    _mm256_store_ps(r, sum_r);
    _mm256_store_ps(g, sum_g);
    _mm256_store_ps(b, sum_b);
    return {lane_total(r), lane_total(g), lane_total(b)};
  }
};
#endif

template <class Lanes>
inline Rgb PhotonMap::lookup(const Vec3& p, const Vec3& n) const {
  // Depth <= log2(N / kLeafPhotons) + 1 < 28 binary levels (median splits); an 8-wide node
  // pushes at most 7 children and spans at least one binary level: 7 * 28 < 256.
  std::uint32_t stack[256];
  int top = 0;
  std::uint32_t node = 0;
  // Stack entries: a wide node, bit 31 set when its subtree lies on the query's surface (the
  // normal and plane tests pass for all its photons: only u < 1 is left to test).
  constexpr std::uint32_t kOnSurface = 1u << 31;
  Lanes lanes(p, n);
  while (true) {
    const bool surface = node & kOnSurface;
    const WideNode& w = m_wide[node & ~kOnSurface];
    unsigned mask = lanes.inside(w);
    const unsigned flat = surface ? 0xffu : (mask ? lanes.on_surface(w) : 0u);
    while (mask) {
      const int i = __builtin_ctz(mask);
      mask &= mask - 1;
      if (!(w.leaf_mask & (1u << i))) {
        stack[top++] = w.child[i] | (flat & (1u << i) ? kOnSurface : 0u);
        continue;
      }
      lanes.add(m_blocks[w.child[i]], (flat & (1u << i)) != 0);
    }
    if (top == 0) break;
    node = stack[--top];
  }
  const Rgb sum = lanes.total();
  const float norm = 2.0f / kPi;
  return {sum.r * norm, sum.g * norm, sum.b * norm};
}

#if THAW_AVX2_DISPATCH
THAW_TARGET_AVX2 Rgb PhotonMap::lookup_avx2(const Vec3& p, const Vec3& n) const {
  return lookup<LookupAvx2>(p, n);
}
#endif
#endif  // __SSE2__

Rgb PhotonMap::irradiance_at(SimdLevel level, const Vec3& p, const Vec3& n) const {
  if (m_wide.empty()) return {};
#if defined(__SSE2__)
#if THAW_AVX2_DISPATCH
  if (level == SimdLevel::avx2) return lookup_avx2(p, n);
#endif
  (void)level;
  return lookup<LookupSse>(p, n);
#else
  (void)level;
  std::uint32_t stack[256];  // as in lookup()
  int top = 0;
  std::uint32_t node = 0;
  float sr[kLeafPhotons] = {}, sg[kLeafPhotons] = {}, sb[kLeafPhotons] = {};
  while (true) {
    const WideNode& w = m_wide[node];
    for (int i = 0; i < kWidth; ++i) {
      if (!(w.lo[0][i] <= p.x && p.x <= w.hi[0][i] && w.lo[1][i] <= p.y && p.y <= w.hi[1][i] &&
            w.lo[2][i] <= p.z && p.z <= w.hi[2][i]))
        continue;
      if (!(w.leaf_mask & (1u << i))) {
        stack[top++] = w.child[i];
        continue;
      }
      const PhotonBlock& b = m_blocks[w.child[i]];
      for (std::uint32_t k = 0; k < kLeafPhotons; ++k) {
        const Vec3 v{b.x[k] - p.x, b.y[k] - p.y, b.z[k] - p.z};
        const float u = dot(v, v) * b.inv_r2[k];
        const float cos_n = b.nx[k] * n.x + b.ny[k] * n.y + b.nz[k] * n.z;
        const float h = dot(v, n);
        if (!(u < 1.0f) || !(cos_n >= kMinNormalCos) ||
            !(h * h * b.inv_r2[k] <= kMaxPlaneDistance * kMaxPlaneDistance))
          continue;
        const float wgt = (1.0f - u) * b.inv_r2[k];
        sr[k] += wgt * b.r[k];
        sg[k] += wgt * b.g[k];
        sb[k] += wgt * b.b[k];
      }
    }
    if (top == 0) break;
    node = stack[--top];
  }
  float tr = 0, tg = 0, tb = 0;
  for (std::uint32_t k = 0; k < kLeafPhotons; ++k) {
    tr += sr[k];
    tg += sg[k];
    tb += sb[k];
  }
  const float norm = 2.0f / kPi;
  return {tr * norm, tg * norm, tb * norm};
#endif
}

}  // namespace thaw::render::photon
