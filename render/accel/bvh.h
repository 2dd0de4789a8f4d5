#pragma once
// Bounding volume hierarchy over any primitives given by their boxes: binned SAH build
// (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"), built in parallel
// (OpenMP tasks) for large inputs, flattened depth-first into 32-byte binary nodes (first child
// follows its parent; pbrt-v4 LinearBVHNode). For traversal the binary tree is collapsed into
// 4-wide nodes (children's boxes stored as SoA, tested together with SSE: Dammertz et al. 2008
// "Shallow bounding volume hierarchies for fast SIMD ray tracing"; Embree's BVH4), which halves the
// node visits and measured 1.5-2x faster than binary traversal on the S1 meshes. Traversal is
// ordered front-to-back with a precomputed inverse direction and a conservative slab test
// (pbrt-v4 Bounds3::IntersectP: far distances scaled by 1 + 2 gamma(3)). Each query (closest hit,
// any hit, region) is one traversal templated on the node width, the node test and the leaf test,
// so both widths and both instruction sets share it and primitive intersection inlines. Knows
// nothing about what the primitives are.
// Closest-hit and any-hit rays traverse a second collapse of the same binary tree into 8-wide
// nodes (Embree's BVH8; Benthin et al. 2012) where the tree is large (on the default film, rays
// starting on a surface inside the nested shells visited 16 4-wide nodes each; a small tree such
// as S4's 16 spheres stays 4-wide, where the 8-wide one was slower). The eight slab tests run as
// one AVX2 instruction sequence where the CPU has AVX2 (checked once at run time: the build targets
// baseline x86-64), else as two SSE halves with the same operations in the same order (no FMA),
// so both give the same masks and entry distances, visit nodes in the same order and return the
// same hit on every machine (accel/simd_level.h; test_bvh checks the two paths against each other).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "render/accel/simd_level.h"
#include "render/math/aabb.h"
#include "render/math/ray.h"

namespace thaw::render {

struct alignas(32) BvhNode {
  Vec3 lo;
  /// leaf: index of the first primitive (in build order); interior: index of the second child
  std::uint32_t offset;
  Vec3 hi;
  /// leaf: number of primitives (> 0); interior: 0
  std::uint32_t count;
};
static_assert(sizeof(BvhNode) == 32);

/// W children of a collapsed node: bounds as structure of arrays (one SIMD register per plane),
/// child references and leaf sizes. Unused slots have an empty box (lo = +inf, hi = -inf).
template <int W>
struct alignas(64) BvhWideNode {
  /// planes[0..5] = lo_x, hi_x, lo_y, hi_y, lo_z, hi_z of the W children
  float planes[6][W];
  /// leaf: first primitive; interior: index of the child node
  std::uint32_t child[W];
  /// leaf: number of primitives (> 0); interior or unused: 0
  std::uint32_t count[W];
};
using Bvh4Node = BvhWideNode<4>;
using Bvh8Node = BvhWideNode<8>;
static_assert(sizeof(Bvh4Node) == 128);
static_assert(sizeof(Bvh8Node) == 256);

struct BvhBuildOptions {
  /// leaves hold at most this many primitives unless they cannot be split
  int max_leaf_size = 4;
  /// SAH cost of one node traversal relative to one primitive test
  float traversal_cost = 1.0f;
  /// primitives are tested this many at a time (SIMD leaves): the SAH counts ceil(n / block)
  int block_size = 4;
  /// inputs at least this large are built with OpenMP tasks
  std::size_t parallel_threshold = 4096;
  /// rays traverse 8-wide nodes for at least this many primitives, 4-wide ones below: on S4's 18
  /// primitives the 8-wide tree cost 5 % more, on the default film's 23k it saves 7 %
  /// (docs/benchmarks.md)
  std::size_t wide8_min_primitives = 256;
};

class Bvh {
 public:
  Bvh() = default;
  /// Builds over `bounds` (one box per primitive). Afterwards `order()[i]` is the input index of
  /// the i-th primitive as the leaves reference them: callers store their primitives in that order.
  /// `tested_alone` (empty, or one flag per primitive): primitives the leaf test cannot take
  /// BvhBuildOptions::block_size at a time, so the SAH counts each as one test.
  explicit Bvh(std::span<const Aabb> bounds, const BvhBuildOptions& options = {},
               std::span<const std::uint8_t> tested_alone = {});

  /// The binary tree (build result); region queries use wide_nodes(), rays wide8_nodes() (empty
  /// below BvhBuildOptions::wide8_min_primitives: then wide_nodes()).
  const std::vector<BvhNode>& nodes() const { return m_nodes; }
  const std::vector<Bvh4Node>& wide_nodes() const { return m_wide; }
  const std::vector<Bvh8Node>& wide8_nodes() const { return m_wide8; }
  const std::vector<std::uint32_t>& order() const { return m_order; }
  bool empty() const { return m_nodes.empty(); }
  /// Depth of the deepest leaf (root = 1).
  int depth() const { return m_depth; }

  /// Per-ray constants of the slab test.
  struct RayData {
    Vec3 origin, inv_direction;
    /// index into BvhWideNode::planes of the near plane per axis (the far one is near ^ 1)
    int near_plane[3];
#if defined(__SSE2__)
    // The same, broadcast once per ray rather than once per node.
    __m128 o4[3], inv4[3];
#endif
    explicit RayData(const Ray& ray) : origin(ray.origin) {
      // A zero component would give inf * 0 = NaN in the slab test; a tiny one keeps every
      // product finite and changes nothing measurable (Embree does the same).
      for (int i = 0; i < 3; ++i) {
        float d = ray.direction[i];
        if (std::fabs(d) < 1e-20f) d = std::copysign(1e-20f, d);
        inv_direction[i] = 1.0f / d;
        near_plane[i] = 2 * i + (inv_direction[i] < 0.0f ? 1 : 0);
#if defined(__SSE2__)
        o4[i] = _mm_set1_ps(origin[i]);
        inv4[i] = _mm_set1_ps(inv_direction[i]);
#endif
      }
    }
  };

  /// Closest-hit traversal. `leaf(first, count, t_max)` tests primitives [first, first+count),
  /// may lower `t_max` and returns true if it found a closer hit. Returns whether any leaf did.
  /// Runs the simd_level() path; intersect_at() runs a given one (both give the same result).
  template <class LeafFn>
  bool intersect(const RayData& ray, float& t_max, LeafFn&& leaf) const {
    return intersect_at(simd_level(), ray, t_max, leaf);
  }
  template <class LeafFn>
  bool intersect_at(SimdLevel level, const RayData& ray, float& t_max, LeafFn&& leaf) const;

  /// Any-hit traversal: stops as soon as `leaf(first, count, t_max)` returns true.
  template <class LeafFn>
  bool occluded(const RayData& ray, float t_max, LeafFn&& leaf) const {
    return occluded_at(simd_level(), ray, t_max, leaf);
  }
  template <class LeafFn>
  bool occluded_at(SimdLevel level, const RayData& ray, float t_max, LeafFn&& leaf) const;

  /// Region query: visits the leaves whose boxes pass `box_test(lo, hi)` (a conservative test of
  /// a region, e.g. a shadow cone) until `leaf(first, count)` returns true; returns whether one
  /// did. Subtrees whose box fails the test are skipped whole.
  template <class BoxTest, class LeafFn>
  bool any_leaf(BoxTest&& box_test, LeafFn&& leaf) const;

  /// The same with a box test of a node's four children at once: `boxes_test(planes)` gets
  /// Bvh4Node::planes and returns the mask of the children to enter (never an unused slot).
  template <class BoxesTest, class LeafFn>
  bool any_leaf_wide(const BoxesTest& boxes_test, LeafFn&& leaf) const {
    return any_leaf_in<4>(boxes_test, leaf);
  }

  /// The same over the 8-wide nodes (wide8_nodes() must not be empty): `boxes8(planes)` gets
  /// Bvh8Node::planes. `boxes8_avx2`, a functor whose call operator is THAW_TARGET_AVX2, is
  /// used instead where simd_level() is avx2. The leaves found are the same either way.
  template <class Boxes8, class Boxes8Avx2, class LeafFn>
  bool any_leaf_wide8(const Boxes8& boxes8, const Boxes8Avx2& boxes8_avx2, LeafFn&& leaf) const {
#if THAW_AVX2_DISPATCH
    if (simd_level() == SimdLevel::avx2) return any_leaf_avx2<8>(boxes8_avx2, leaf);
#else
    (void)boxes8_avx2;
#endif
    return any_leaf_in<8>(boxes8, leaf);
  }

  /// Slab test of the W children of a W-wide node (W a multiple of 4) on the baseline path: bit i
  /// of the result is set if child i is met within (0, t_max); its entry distance is t_enter[i].
  /// SSE, four children at a time (scalar without SSE).
  template <int W>
  struct Children {
    const RayData& r;
    explicit Children(const RayData& ray) : r(ray) {}
    int operator()(const BvhWideNode<W>& n, float t_max, float t_enter[W]) const;
  };
  using Children4 = Children<4>;
  using Children8 = Children<8>;
#if THAW_AVX2_DISPATCH
  /// Children8 in one AVX2 pass: the same operations in the same order, so the same bits.
  struct Children8Avx2 {
    __m256 o[3], inv[3];
    int near_plane[3];
    THAW_TARGET_AVX2 explicit Children8Avx2(const RayData& ray);
    THAW_TARGET_AVX2 int operator()(const Bvh8Node& n, float t_max, float t_enter[8]) const;
  };
#endif

 private:
  template <int W>
  std::uint32_t collapse(std::vector<BvhWideNode<W>>& out, std::uint32_t binary_index) const;
  /// The W-wide tree: rays use the 8-wide one where it exists, region queries either.
  template <int W>
  const std::vector<BvhWideNode<W>>& tree() const {
    if constexpr (W == 8) {
      return m_wide8;
    } else {
      static_assert(W == 4);
      return m_wide;
    }
  }
  // The three traversals, one per query, over the W-wide tree with the node test `Children`
  // (or `BoxesTest`) inlined: the SSE entry points call them directly, the AVX2 ones below
  // instantiate them in functions compiled for AVX2.
  template <int W, class Children, class LeafFn>
  [[gnu::always_inline]] inline bool closest(const RayData& ray, float& t_max, LeafFn& leaf) const;
  template <int W, class Children, class LeafFn>
  [[gnu::always_inline]] inline bool any(const RayData& ray, float t_max, LeafFn& leaf) const;
  template <int W, class BoxesTest, class LeafFn>
  [[gnu::always_inline]] inline bool any_leaf_in(const BoxesTest& boxes_test, LeafFn& leaf) const;
#if THAW_AVX2_DISPATCH
  template <int W, class BoxesTest, class LeafFn>
  THAW_TARGET_AVX2 bool any_leaf_avx2(const BoxesTest& boxes_test, LeafFn& leaf) const {
    return any_leaf_in<W>(boxes_test, leaf);
  }
  template <class LeafFn>
  THAW_TARGET_AVX2 bool closest8_avx2(const RayData& ray, float& t_max, LeafFn& leaf) const {
    return closest<8, Children8Avx2>(ray, t_max, leaf);
  }
  template <class LeafFn>
  THAW_TARGET_AVX2 bool any8_avx2(const RayData& ray, float t_max, LeafFn& leaf) const {
    return any<8, Children8Avx2>(ray, t_max, leaf);
  }
#endif
  std::vector<BvhNode> m_nodes;
  std::vector<Bvh4Node> m_wide;
  std::vector<Bvh8Node> m_wide8;
  std::vector<std::uint32_t> m_order;
  int m_depth = 0;
};

// Depth is bounded by the build (SAH splits below depth 48, then median splits of at most 2^31
// primitives: at most 80 binary levels, so at most 79 interior ones). A traversal keeps on its
// stack at most W - 1 children of each W-wide node on the current path (any_leaf_in pushes all W
// and pops one at once), and each W-wide node descends at least one binary level: (W - 1) * 80
// entries can never overflow.
inline constexpr int kBvhMaxBinaryDepth = 80;
template <int W>
inline constexpr int kBvhStackSize = (W - 1) * kBvhMaxBinaryDepth;

template <int W>
inline int Bvh::Children<W>::operator()(const BvhWideNode<W>& n, float t_max,
                                        float t_enter[W]) const {
  static_assert(W % 4 == 0);
  const float scale = 1.0f + 2.0f * gamma_bound(3);
#if defined(__SSE2__)
  const __m128 ox = r.o4[0], oy = r.o4[1], oz = r.o4[2];
  const __m128 ix = r.inv4[0], iy = r.inv4[1], iz = r.inv4[2];
  const float* nx = n.planes[r.near_plane[0]];
  const float* ny = n.planes[r.near_plane[1]];
  const float* nz = n.planes[r.near_plane[2]];
  const float* fx = n.planes[r.near_plane[0] ^ 1];
  const float* fy = n.planes[r.near_plane[1] ^ 1];
  const float* fz = n.planes[r.near_plane[2] ^ 1];
  int mask = 0;
  for (int h = 0; h < W; h += 4) {
    const __m128 tnx = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(nx + h), ox), ix);
    const __m128 tny = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(ny + h), oy), iy);
    const __m128 tnz = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(nz + h), oz), iz);
    const __m128 tfx = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(fx + h), ox), ix);
    const __m128 tfy = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(fy + h), oy), iy);
    const __m128 tfz = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(fz + h), oz), iz);
    const __m128 t_near = _mm_max_ps(_mm_max_ps(tnx, tny), _mm_max_ps(tnz, _mm_setzero_ps()));
    const __m128 t_far = _mm_mul_ps(
        _mm_min_ps(_mm_min_ps(tfx, tfy), _mm_min_ps(tfz, _mm_set1_ps(t_max))), _mm_set1_ps(scale));
    _mm_storeu_ps(t_enter + h, t_near);
    mask |= _mm_movemask_ps(_mm_cmple_ps(t_near, t_far)) << h;
  }
  return mask;
#else
  int mask = 0;
  for (int i = 0; i < W; ++i) {
    const float tnx = (n.planes[r.near_plane[0]][i] - r.origin.x) * r.inv_direction.x;
    const float tny = (n.planes[r.near_plane[1]][i] - r.origin.y) * r.inv_direction.y;
    const float tnz = (n.planes[r.near_plane[2]][i] - r.origin.z) * r.inv_direction.z;
    const float tfx = (n.planes[r.near_plane[0] ^ 1][i] - r.origin.x) * r.inv_direction.x;
    const float tfy = (n.planes[r.near_plane[1] ^ 1][i] - r.origin.y) * r.inv_direction.y;
    const float tfz = (n.planes[r.near_plane[2] ^ 1][i] - r.origin.z) * r.inv_direction.z;
    t_enter[i] = std::max(std::max(tnx, tny), std::max(tnz, 0.0f));
    const float t_far = std::min(std::min(tfx, tfy), std::min(tfz, t_max)) * scale;
    if (t_enter[i] <= t_far) mask |= 1 << i;
  }
  return mask;
#endif
}

#if THAW_AVX2_DISPATCH
THAW_TARGET_AVX2 inline Bvh::Children8Avx2::Children8Avx2(const RayData& ray) {
  for (int i = 0; i < 3; ++i) {
    o[i] = _mm256_set1_ps(ray.origin[i]);
    inv[i] = _mm256_set1_ps(ray.inv_direction[i]);
    near_plane[i] = ray.near_plane[i];
  }
}

THAW_TARGET_AVX2 inline int Bvh::Children8Avx2::operator()(const Bvh8Node& n, float t_max,
                                                           float t_enter[8]) const {
  const float scale = 1.0f + 2.0f * gamma_bound(3);
  // Children8's operations lane for lane: (plane - o) * inv, max/min in the same operand order.
  const __m256 tnx =
      _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.planes[near_plane[0]]), o[0]), inv[0]);
  const __m256 tny =
      _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.planes[near_plane[1]]), o[1]), inv[1]);
  const __m256 tnz =
      _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.planes[near_plane[2]]), o[2]), inv[2]);
  const __m256 tfx =
      _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.planes[near_plane[0] ^ 1]), o[0]), inv[0]);
  const __m256 tfy =
      _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.planes[near_plane[1] ^ 1]), o[1]), inv[1]);
  const __m256 tfz =
      _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.planes[near_plane[2] ^ 1]), o[2]), inv[2]);
  const __m256 t_near =
      _mm256_max_ps(_mm256_max_ps(tnx, tny), _mm256_max_ps(tnz, _mm256_setzero_ps()));
  const __m256 t_far = _mm256_mul_ps(
      _mm256_min_ps(_mm256_min_ps(tfx, tfy), _mm256_min_ps(tfz, _mm256_set1_ps(t_max))),
      _mm256_set1_ps(scale));
  _mm256_storeu_ps(t_enter, t_near);
  return _mm256_movemask_ps(_mm256_cmp_ps(t_near, t_far, _CMP_LE_OQ));
}
#endif

template <int W, class Children, class LeafFn>
inline bool Bvh::closest(const RayData& ray, float& t_max, LeafFn& leaf) const {
  const std::vector<BvhWideNode<W>>& nodes = tree<W>();
  if (nodes.empty()) return false;
  const Children children(ray);
  struct Entry {
    std::uint32_t ref, count;
    float t;
  };
  Entry stack[kBvhStackSize<W>];
  int sp = 0;
  bool hit = false;
  // The root's own box is the union of its children's: testing the children suffices.
  std::uint32_t ref = 0, count = 0;
  while (true) {
    if (count > 0) {
      if (leaf(ref, count, t_max)) hit = true;
    } else {
      const BvhWideNode<W>& n = nodes[ref];
      alignas(32) float t[W];
      auto mask = static_cast<unsigned>(children(n, t_max, t));
      if (mask != 0) {
        const int first = __builtin_ctz(mask);
        const unsigned rest = mask & (mask - 1);
        if (rest == 0) {  // one child hit: the common case deep in the tree
          ref = n.child[first];
          count = n.count[first];
          continue;
        }
        if ((rest & (rest - 1)) == 0) {  // two: visit the nearer, push the farther
          int a = first, b = __builtin_ctz(rest);
          if (t[b] < t[a]) std::swap(a, b);
          stack[sp++] = {n.child[b], n.count[b], t[b]};
          ref = n.child[a];
          count = n.count[a];
          continue;
        }
        // Three or more: nearest next, the others on the stack, farthest deepest.
        Entry e[W];
        int k = 0;
        while (mask) {
          const int i = __builtin_ctz(mask);
          mask &= mask - 1;
          const Entry c{n.child[i], n.count[i], t[i]};
          int j = k++;
          while (j > 0 && e[j - 1].t < c.t) {  // sort by decreasing distance
            e[j] = e[j - 1];
            --j;
          }
          e[j] = c;
        }
        for (int j = 0; j < k - 1; ++j) stack[sp++] = e[j];
        ref = e[k - 1].ref;
        count = e[k - 1].count;
        continue;
      }
    }
    // Pop the next subtree that may still hold a closer hit.
    while (true) {
      if (sp == 0) return hit;
      const Entry& e = stack[--sp];
      if (e.t <= t_max) {
        ref = e.ref;
        count = e.count;
        break;
      }
    }
  }
}

template <int W, class Children, class LeafFn>
inline bool Bvh::any(const RayData& ray, float t_max, LeafFn& leaf) const {
  const std::vector<BvhWideNode<W>>& nodes = tree<W>();
  if (nodes.empty()) return false;
  const Children children(ray);
  struct Entry {
    std::uint32_t ref, count;
  };
  Entry stack[kBvhStackSize<W>];
  int sp = 0;
  std::uint32_t ref = 0, count = 0;
  while (true) {
    if (count > 0) {
      if (leaf(ref, count, t_max)) return true;
    } else {
      const BvhWideNode<W>& n = nodes[ref];
      alignas(32) float t[W];
      auto mask = static_cast<unsigned>(children(n, t_max, t));
      if (mask != 0) {
        const int i = __builtin_ctz(mask);
        mask &= mask - 1;
        while (mask) {  // any order will do for an any-hit query
          const int j = __builtin_ctz(mask);
          mask &= mask - 1;
          stack[sp++] = {n.child[j], n.count[j]};
        }
        ref = n.child[i];
        count = n.count[i];
        continue;
      }
    }
    if (sp == 0) return false;
    --sp;
    ref = stack[sp].ref;
    count = stack[sp].count;
  }
}

template <class LeafFn>
bool Bvh::intersect_at(SimdLevel level, const RayData& ray, float& t_max, LeafFn&& leaf) const {
  if (m_wide8.empty()) return closest<4, Children4>(ray, t_max, leaf);
#if THAW_AVX2_DISPATCH
  if (level == SimdLevel::avx2) return closest8_avx2(ray, t_max, leaf);
#endif
  (void)level;
  return closest<8, Children8>(ray, t_max, leaf);
}

template <class LeafFn>
bool Bvh::occluded_at(SimdLevel level, const RayData& ray, float t_max, LeafFn&& leaf) const {
  if (m_wide8.empty()) return any<4, Children4>(ray, t_max, leaf);
#if THAW_AVX2_DISPATCH
  if (level == SimdLevel::avx2) return any8_avx2(ray, t_max, leaf);
#endif
  (void)level;
  return any<8, Children8>(ray, t_max, leaf);
}

template <class BoxTest, class LeafFn>
bool Bvh::any_leaf(BoxTest&& box_test, LeafFn&& leaf) const {
  // One child box at a time: the mask any_leaf_wide takes, from four scalar tests.
  return any_leaf_wide(
      [&](const float(&planes)[6][4]) {
        unsigned mask = 0;
        for (int i = 0; i < 4; ++i) {
          const Vec3 lo{planes[0][i], planes[2][i], planes[4][i]};
          const Vec3 hi{planes[1][i], planes[3][i], planes[5][i]};
          if (!(lo.x > hi.x) && box_test(lo, hi)) mask |= 1u << i;  // a used slot, in the region
        }
        return mask;
      },
      std::forward<LeafFn>(leaf));
}

template <int W, class BoxesTest, class LeafFn>
inline bool Bvh::any_leaf_in(const BoxesTest& boxes_test, LeafFn& leaf) const {
  const std::vector<BvhWideNode<W>>& nodes = tree<W>();
  if (nodes.empty()) return false;
  struct Entry {
    std::uint32_t ref, count;
  };
  Entry stack[kBvhStackSize<W>];
  int sp = 0;
  Entry e{0, 0};  // the root: its children are tested
  while (true) {
    if (e.count > 0) {
      if (leaf(e.ref, e.count)) return true;
    } else {
      const BvhWideNode<W>& n = nodes[e.ref];
      auto mask = static_cast<unsigned>(boxes_test(n.planes));
      while (mask) {  // in child order, as any_leaf pushes them
        const int i = __builtin_ctz(mask);
        mask &= mask - 1;
        stack[sp++] = {n.child[i], n.count[i]};
      }
    }
    if (sp == 0) return false;
    e = stack[--sp];
  }
}

}  // namespace thaw::render
