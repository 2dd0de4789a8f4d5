#pragma once
// Bounding volume hierarchy over any primitives given by their boxes: binned SAH build
// (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"), built in parallel
// (OpenMP tasks) for large inputs, flattened depth-first into 32-byte nodes (first child follows
// its parent; pbrt-v4 LinearBVHNode). Traversal is ordered front-to-back with a precomputed
// inverse direction and a conservative slab test (pbrt-v4 Bounds3::IntersectP, t_max scaled by
// 1 + 2 gamma(3)), and templated on the leaf test so primitive intersection inlines.
// Knows nothing about what the primitives are.
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

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

struct BvhBuildOptions {
  /// leaves hold at most this many primitives unless they cannot be split
  int max_leaf_size = 4;
  /// SAH cost of one node traversal relative to one primitive test
  float traversal_cost = 1.0f;
  /// inputs at least this large are built with OpenMP tasks
  std::size_t parallel_threshold = 4096;
};

class Bvh {
 public:
  Bvh() = default;
  /// Builds over `bounds` (one box per primitive). Afterwards `order()[i]` is the input index of
  /// the i-th primitive as the leaves reference them: callers store their primitives in that order.
  explicit Bvh(std::span<const Aabb> bounds, const BvhBuildOptions& options = {});

  const std::vector<BvhNode>& nodes() const { return m_nodes; }
  const std::vector<std::uint32_t>& order() const { return m_order; }
  bool empty() const { return m_nodes.empty(); }
  /// Depth of the deepest leaf (root = 1).
  int depth() const { return m_depth; }

  /// Per-ray constants of the slab test.
  struct RayData {
    Vec3 origin, inv_direction;
    explicit RayData(const Ray& ray) : origin(ray.origin) {
      // A zero component would give inf * 0 = NaN in the slab test; a tiny one keeps every
      // product finite and changes nothing measurable (Embree does the same).
      for (int i = 0; i < 3; ++i) {
        float d = ray.direction[i];
        if (std::fabs(d) < 1e-20f) d = std::copysign(1e-20f, d);
        inv_direction[i] = 1.0f / d;
      }
    }
  };

  /// Closest-hit traversal. `leaf(first, count, t_max)` tests primitives [first, first+count),
  /// may lower `t_max` and returns true if it found a closer hit. Returns whether any leaf did.
  template <class LeafFn>
  bool intersect(const RayData& ray, float& t_max, LeafFn&& leaf) const;

  /// Any-hit traversal: stops as soon as `leaf(first, count, t_max)` returns true.
  template <class LeafFn>
  bool occluded(const RayData& ray, float t_max, LeafFn&& leaf) const;

  /// Slab test of one node: entry distance in `t_enter` if the ray meets it within (0, t_max).
  static bool hit_node(const BvhNode& n, const RayData& r, float t_max, float& t_enter) {
    const float tx0 = (n.lo.x - r.origin.x) * r.inv_direction.x;
    const float tx1 = (n.hi.x - r.origin.x) * r.inv_direction.x;
    const float ty0 = (n.lo.y - r.origin.y) * r.inv_direction.y;
    const float ty1 = (n.hi.y - r.origin.y) * r.inv_direction.y;
    const float tz0 = (n.lo.z - r.origin.z) * r.inv_direction.z;
    const float tz1 = (n.hi.z - r.origin.z) * r.inv_direction.z;
    const float t_near = std::max(std::max(std::min(tx0, tx1), std::min(ty0, ty1)),
                                  std::max(std::min(tz0, tz1), 0.0f));
    float t_far = std::min(std::min(std::max(tx0, tx1), std::max(ty0, ty1)),
                           std::min(std::max(tz0, tz1), t_max));
    // Conservative: rounding in the slab distances must not cull a primitive the exact test hits.
    t_far *= 1.0f + 2.0f * gamma_bound(3);
    t_enter = t_near;
    return t_near <= t_far;
  }

 private:
  std::vector<BvhNode> m_nodes;
  std::vector<std::uint32_t> m_order;
  int m_depth = 0;
};

// Depth is bounded by the build (SAH splits below depth 48, then median splits), so 128 entries
// can never overflow.
inline constexpr int kBvhStackSize = 128;

template <class LeafFn>
bool Bvh::intersect(const RayData& ray, float& t_max, LeafFn&& leaf) const {
  if (m_nodes.empty()) return false;
  const BvhNode* nodes = m_nodes.data();
  float t_root;
  if (!hit_node(nodes[0], ray, t_max, t_root)) return false;
  struct Entry {
    std::uint32_t node;
    float t;
  };
  Entry stack[kBvhStackSize];
  int sp = 0;
  std::uint32_t index = 0;
  bool hit = false;
  while (true) {
    const BvhNode& n = nodes[index];
    if (n.count > 0) {
      if (leaf(n.offset, n.count, t_max)) hit = true;
    } else {
      std::uint32_t c0 = index + 1, c1 = n.offset;
      float t0, t1;
      const bool h0 = hit_node(nodes[c0], ray, t_max, t0);
      const bool h1 = hit_node(nodes[c1], ray, t_max, t1);
      if (h0 && h1) {
        if (t1 < t0) {
          std::swap(c0, c1);
          std::swap(t0, t1);
        }
        stack[sp++] = {c1, t1};
        index = c0;
        continue;
      }
      if (h0) { index = c0; continue; }
      if (h1) { index = c1; continue; }
    }
    // Pop the next subtree that may still hold a closer hit.
    while (true) {
      if (sp == 0) return hit;
      const Entry& e = stack[--sp];
      if (e.t <= t_max) {
        index = e.node;
        break;
      }
    }
  }
}

template <class LeafFn>
bool Bvh::occluded(const RayData& ray, float t_max, LeafFn&& leaf) const {
  if (m_nodes.empty()) return false;
  const BvhNode* nodes = m_nodes.data();
  float t_enter;
  if (!hit_node(nodes[0], ray, t_max, t_enter)) return false;
  std::uint32_t stack[kBvhStackSize];
  int sp = 0;
  std::uint32_t index = 0;
  while (true) {
    const BvhNode& n = nodes[index];
    if (n.count > 0) {
      if (leaf(n.offset, n.count, t_max)) return true;
    } else {
      const std::uint32_t c0 = index + 1, c1 = n.offset;
      float t0, t1;
      const bool h0 = hit_node(nodes[c0], ray, t_max, t0);
      const bool h1 = hit_node(nodes[c1], ray, t_max, t1);
      if (h0 && h1) {
        stack[sp++] = c1;
        index = c0;
        continue;
      }
      if (h0) { index = c0; continue; }
      if (h1) { index = c1; continue; }
    }
    if (sp == 0) return false;
    index = stack[--sp];
  }
}

}  // namespace thaw::render
