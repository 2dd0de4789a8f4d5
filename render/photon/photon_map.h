#pragma once
// Stored caustic photons and the irradiance density estimate on diffuse surfaces.
// Irradiance at p with unit normal n: E = sum_p Phi_p K_p(|x_p - p|), each photon spread over a
// disc of its own radius r_p with the Epanechnikov kernel K_p(d) = 2 / (pi r_p^2) (1 - d^2 / r_p^2)
// (Silverman 1986, "Density Estimation", table 3.1, in 2D; the "scatter" form of a density
// estimate). Every K_p integrates to 1, so photons keep their power exactly, and a uniform photon
// density of flux per area F returns exactly E = F, in the units of the photons' power per area:
// the same units as direct light when Phi = I Omega / N (caustic_map.h).
// Radius: each photon's r_p = r sqrt(K / n_r), clamped to [r, 8r], where n_r estimates the photons
// within r of it from the count of the 8 grid cells (2r wide) around it (O(1)) and K =
// `photons_per_disc`: the focused, well sampled caustic keeps the sharp kernel r, while the faint
// light reflected off the ice and the halo around the caustic, carried by few photons, is spread
// into a smooth glow instead of grain (the adaptive-kernel idea of Silverman sec. 5.3, the pilot
// density taken per cell). r_p is continuous in the count, so a uniform region (cell counts
// scattering around K) keeps radii within a few percent of r instead of a cell pattern of two
// kernels. The price: a caustic's edges, where cells are partly empty, get a wider kernel.
// Photons of other surfaces are rejected: a photon counts only if its stored normal is within
// ~25 degrees of n (cos > 0.9) and it lies within r_p / 4 of the tangent plane (a corner, the far
// side of a thin wall, a ball resting on the floor).
// Lookup: a bounding volume hierarchy over the photons' kernel balls (each photon's box is its
// position +- r_p; nodes bound their photons' boxes; leaves of kLeafPhotons photons, the last
// one possibly fewer),
// collapsed to 8-wide nodes and 8-photon leaf blocks, both tested with AVX2 where the CPU has it
// (render/accel/simd_level.h), else as two SSE halves: the same operations lane for lane and the
// same order of the final sum, so both give the same bits), descended only into nodes
// whose box contains the query point, so a query examines about the
// photons whose kernels reach it, whatever their radii (the "scatter" form of the estimate as a
// point-in-box query, the reverse of a k-nearest-neighbour search). It replaced seven hashed
// grids, one per radius class, whose 2 x 2 x 2 cells of 2 r_class gave 8.6 candidates per
// contributing photon on the default film (docs/benchmarks.md). The sum is taken in a fixed
// order (the tree's, built from the input order), so results do not depend on threads. Built
// once, immutable, thread-safe to query. Knows nothing about lights or tracing.
// Subtrees on one surface: where a subtree's photons share one normal (bitwise) that passes the
// normal test and its box of positions lies within r_min / 4 of the query's tangent plane (with a
// margin far beyond float rounding), every photon in it passes both tests, so below it only the
// kernel test u < 1 is evaluated: the same sum, a quarter fewer operations per photon (the
// default film's floor photons all qualify at the root's children).
#include <cstdint>
#include <vector>

#include "render/accel/simd_level.h"
#include "render/math/color.h"
#include "render/math/vec3.h"

namespace thaw::render::photon {

struct Photon {
  Vec3 position;
  /// unit geometric normal on the side the photon arrived from
  Vec3 normal;
  /// power [light units x sr, e.g. W for a light in W/sr]
  Rgb power;
  /// 1 / r_p^2 of its kernel [1 / scene units^2] (set by PhotonMap)
  float inv_radius2 = 0;
};

class PhotonMap {
 public:
  /// The largest kernel radius over the base radius r (photons sparser than K per disc of r).
  static constexpr float kMaxRadiusScale = 8.0f;
  /// Photons per leaf of the lookup tree: one AVX2 register's width (fewer nodes and half the
  /// leaf instructions of 4-photon blocks; docs/benchmarks.md has the default film's figures).
  static constexpr std::uint32_t kLeafPhotons = 8;

  PhotonMap() = default;
  /// `radius` > 0 [scene units]; photons among at least `photons_per_disc` (>= 1) keep it,
  /// sparser ones get wider kernels (see above).
  PhotonMap(const std::vector<Photon>& photons, float radius, double photons_per_disc);

  bool empty() const { return m_photons.empty(); }
  std::size_t size() const { return m_photons.size(); }
  /// the base radius r
  float radius() const { return m_radius; }
  /// The photons with their kernels (inv_radius2 set), in the tree's fixed order.
  const std::vector<Photon>& photons() const { return m_photons; }
  /// Leaf blocks of the lookup tree (every one full but the last: ceil(size / kLeafPhotons)).
  std::size_t leaf_blocks() const { return m_blocks.size(); }

  /// Irradiance [power per area] at `p` on a surface with unit normal `n` (facing the side the
  /// light is wanted on). Runs the simd_level() path; irradiance_at() a given one (both give the
  /// same bits).
  Rgb irradiance(const Vec3& p, const Vec3& n) const { return irradiance_at(simd_level(), p, n); }
  Rgb irradiance_at(SimdLevel level, const Vec3& p, const Vec3& n) const;

 private:
  /// A node of the binary build tree: the box of its photons' kernel balls; a leaf (count > 0)
  /// holds photons [first, first + count), an inner node (count = 0) has children first and
  /// first + 1.
  struct Node {
    Vec3 lo, hi;
    std::uint32_t first = 0, count = 0;
    /// its photons: m_photons[begin, end)
    std::uint32_t begin = 0, end = 0;
  };
  /// Children per node of the traversal tree.
  static constexpr int kWidth = 8;
  /// The traversal tree: the binary tree collapsed into 8-wide nodes, the children's boxes as
  /// structure of arrays (tested together with AVX2 or two SSE halves, as render/accel/bvh.h
  /// does for rays). child[i]: a WideNode index, or for a leaf (leaf bit i set) a PhotonBlock
  /// index; unused slots have an empty box. Per child also what decides whether its subtree lies
  /// on one surface (see above): its photons' box of positions, their largest 1 / r_p^2 and their
  /// common normal (bit i of one_normal set when they have one).
  struct alignas(32) WideNode {
    float lo[3][kWidth], hi[3][kWidth];
    float pos_lo[3][kWidth], pos_hi[3][kWidth];
    float max_inv_r2[kWidth];
    float normal[3][kWidth];
    std::uint32_t child[kWidth];
    std::uint32_t leaf_mask = 0;
    std::uint32_t one_normal = 0;
  };
  /// The (up to) kLeafPhotons photons of a leaf as structure of arrays, tested together; unused
  /// lanes have zero power and inv_radius2 (they add 0).
  struct alignas(32) PhotonBlock {
    float x[kLeafPhotons], y[kLeafPhotons], z[kLeafPhotons], nx[kLeafPhotons], ny[kLeafPhotons],
        nz[kLeafPhotons], inv_r2[kLeafPhotons], r[kLeafPhotons], g[kLeafPhotons], b[kLeafPhotons];
  };
  struct LookupSse;
  struct LookupAvx2;
  /// The lookup with the node and leaf tests of `Lanes` (LookupSse: SSE halves; LookupAvx2).
  template <class Lanes>
  [[gnu::always_inline]] inline Rgb lookup(const Vec3& p, const Vec3& n) const;
  THAW_TARGET_AVX2 Rgb lookup_avx2(const Vec3& p, const Vec3& n) const;
  /// Builds the subtree of m_photons[begin, end) into nodes[node].
  void build(std::vector<Node>& nodes, std::uint32_t node, std::uint32_t begin, std::uint32_t end);
  /// Collapses binary node `node` (interior) into m_wide[wide].
  void collapse(const std::vector<Node>& nodes, std::uint32_t node, std::uint32_t wide);
  /// A leaf's photons as a block; returns its index.
  std::uint32_t add_block(const Node& leaf);
  /// Slot i of `w`: the positions' box, the largest 1 / r^2 and the common normal of `node`.
  void describe(const Node& node, WideNode& w, int i) const;

  std::vector<Photon> m_photons;
  std::vector<WideNode> m_wide;
  std::vector<PhotonBlock> m_blocks;
  float m_radius = 0;
};

}  // namespace thaw::render::photon
