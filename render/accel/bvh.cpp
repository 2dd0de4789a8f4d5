#include "render/accel/bvh.h"

#include <algorithm>

#include "base/check.h"

namespace thaw::render {

namespace {

constexpr int kBins = 16;
// Below this depth the build uses SAH; deeper it splits at the median so the depth (and thus the
// traversal stack) stays bounded even for adversarial inputs.
constexpr int kMaxSahDepth = 48;

struct BuildNode {
  Aabb box;
  std::uint32_t first = 0, count = 0;  // primitive range (leaf) or range covered (interior)
  std::uint32_t right = 0;             // slot of the right child (interior)
  bool leaf = false;
  bool used = false;
};

/// How many primitives of a range are tested in blocks and how many alone.
struct Counts {
  std::uint32_t blocked = 0, alone = 0;
  Counts& operator+=(const Counts& o) {
    blocked += o.blocked, alone += o.alone;
    return *this;
  }
  bool empty() const { return blocked + alone == 0; }
};

struct Builder {
  std::span<const Aabb> bounds;
  std::span<const std::uint8_t> tested_alone;  // empty: every primitive is blockable
  std::vector<Vec3> centroids;
  std::vector<std::uint32_t>& order;
  std::vector<BuildNode>& slots;
  BvhBuildOptions options;

  Counts count_of(std::uint32_t primitive) const {
    const bool alone = !tested_alone.empty() && tested_alone[primitive] != 0;
    return alone ? Counts{0, 1} : Counts{1, 0};
  }

  /// SAH intersection cost of a leaf: blockable primitives tested block_size at a time, the
  /// others one test each (a sphere's quadratic costs as much as a 4-triangle SIMD block, so
  /// counting 4 spheres as one block made S4's leaves hold 4 spheres each).
  float blocks(const Counts& c) const {
    const auto b = static_cast<std::uint32_t>(std::max(1, options.block_size));
    return float((c.blocked + b - 1) / b + c.alone);
  }

  // Builds the subtree for order[begin, end) into slots[slot, slot + 2 (end - begin) - 1):
  // a subtree of m primitives has at most 2m - 1 nodes, so children get disjoint slot ranges and
  // parallel subtrees never write to the same slot (the gaps are squeezed out when flattening).
  int build(std::uint32_t slot, std::uint32_t begin, std::uint32_t end, int depth) {
    BuildNode& node = slots[slot];
    node.used = true;
    Aabb box, cbox;
    for (std::uint32_t i = begin; i < end; ++i) {
      box.extend(bounds[order[i]]);
      cbox.extend(centroids[order[i]]);
    }
    node.box = box;
    node.first = begin;
    node.count = end - begin;
    const std::uint32_t m = end - begin;
    if (m <= 1) {
      node.leaf = true;
      return 1;
    }
    std::uint32_t mid = begin;
    bool split_found = false;
    const Vec3 cext = cbox.extent();
    if (depth < kMaxSahDepth) {
      float best_cost = std::numeric_limits<float>::infinity();
      int best_axis = -1, best_bin = -1;
      for (int axis = 0; axis < 3; ++axis) {
        if (!(cext[axis] > 0.0f)) continue;
        Aabb bin_box[kBins];
        Counts bin_count[kBins] = {};
        const float scale = kBins * (1.0f - 1e-6f) / cext[axis];
        for (std::uint32_t i = begin; i < end; ++i) {
          int b = static_cast<int>((centroids[order[i]][axis] - cbox.lo[axis]) * scale);
          b = std::clamp(b, 0, kBins - 1);
          bin_box[b].extend(bounds[order[i]]);
          bin_count[b] += count_of(order[i]);
        }
        float right_area[kBins];
        Counts right_count[kBins];
        Aabb acc;
        Counts cnt;
        for (int b = kBins - 1; b > 0; --b) {
          acc.extend(bin_box[b]);
          cnt += bin_count[b];
          right_area[b] = acc.area();
          right_count[b] = cnt;
        }
        acc = Aabb{};
        cnt = Counts{};
        for (int b = 0; b < kBins - 1; ++b) {
          acc.extend(bin_box[b]);
          cnt += bin_count[b];
          if (cnt.empty() || right_count[b + 1].empty()) continue;
          const float cost =
              acc.area() * blocks(cnt) + right_area[b + 1] * blocks(right_count[b + 1]);
          if (cost < best_cost) {
            best_cost = cost;
            best_axis = axis;
            best_bin = b;
          }
        }
      }
      if (best_axis >= 0) {
        Counts all;
        for (std::uint32_t i = begin; i < end; ++i) all += count_of(order[i]);
        const float area = box.area();
        const float split_cost =
            options.traversal_cost + (area > 0.0f ? best_cost / area : blocks(all));
        if (m <= static_cast<std::uint32_t>(options.max_leaf_size) && blocks(all) <= split_cost) {
          node.leaf = true;
          return 1;
        }
        const float scale = kBins * (1.0f - 1e-6f) / cext[best_axis];
        const float lo = cbox.lo[best_axis];
        auto* it = std::partition(order.data() + begin, order.data() + end, [&](std::uint32_t p) {
          const int b =
              std::clamp(static_cast<int>((centroids[p][best_axis] - lo) * scale), 0, kBins - 1);
          return b <= best_bin;
        });
        mid = static_cast<std::uint32_t>(it - order.data());
        split_found = mid > begin && mid < end;
      }
    }
    if (!split_found) {
      if (m <= static_cast<std::uint32_t>(options.max_leaf_size)) {
        node.leaf = true;
        return 1;
      }
      // Median split along the widest centroid axis (all centroids equal: any halving works).
      const int axis = max_dimension(cext);
      mid = begin + m / 2;
      std::nth_element(order.data() + begin, order.data() + mid, order.data() + end,
                       [&](std::uint32_t a, std::uint32_t b) {
                         if (centroids[a][axis] != centroids[b][axis])
                           return centroids[a][axis] < centroids[b][axis];
                         return a < b;
                       });
    }
    const std::uint32_t left_slot = slot + 1;
    const std::uint32_t right_slot = slot + 2 * (mid - begin);
    node.right = right_slot;
    int dl = 0, dr = 0;
    if (m >= options.parallel_threshold) {
#pragma omp task shared(dl) default(shared)
      dl = build(left_slot, begin, mid, depth + 1);
      dr = build(right_slot, mid, end, depth + 1);
#pragma omp taskwait
    } else {
      dl = build(left_slot, begin, mid, depth + 1);
      dr = build(right_slot, mid, end, depth + 1);
    }
    return 1 + std::max(dl, dr);
  }
};

}  // namespace

Bvh::Bvh(std::span<const Aabb> bounds, const BvhBuildOptions& options,
         std::span<const std::uint8_t> tested_alone) {
  const std::size_t n = bounds.size();
  if (n == 0) return;
  THAW_CHECK(n < (std::size_t(1) << 31), "too many primitives for a 32-bit BVH");
  m_order.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) m_order[i] = i;
  std::vector<BuildNode> slots(2 * n - 1);
  THAW_CHECK(tested_alone.empty() || tested_alone.size() == n,
             "tested_alone needs one flag per primitive");
  Builder builder{bounds, tested_alone, {}, m_order, slots, options};
  builder.centroids.resize(n);
  for (std::size_t i = 0; i < n; ++i) builder.centroids[i] = bounds[i].center();
  if (n >= options.parallel_threshold) {
#pragma omp parallel
#pragma omp single
    m_depth = builder.build(0, 0, static_cast<std::uint32_t>(n), 0);
  } else {
    m_depth = builder.build(0, 0, static_cast<std::uint32_t>(n), 0);
  }
  // Flatten depth-first: left child right after its parent, right child index in `offset`.
  m_nodes.reserve(2 * n - 1);
  struct Item {
    std::uint32_t slot;
    std::int64_t parent;  // flat index of the parent whose `offset` must point here, or -1
  };
  std::vector<Item> todo{{0, -1}};
  while (!todo.empty()) {
    const Item item = todo.back();
    todo.pop_back();
    const BuildNode& b = slots[item.slot];
    const auto flat = static_cast<std::uint32_t>(m_nodes.size());
    if (item.parent >= 0) m_nodes[static_cast<std::size_t>(item.parent)].offset = flat;
    BvhNode node{};
    node.lo = b.box.lo;
    node.hi = b.box.hi;
    if (b.leaf) {
      node.offset = b.first;
      node.count = b.count;
      m_nodes.push_back(node);
    } else {
      node.count = 0;
      m_nodes.push_back(node);
      todo.push_back({b.right, flat});      // right: visited after the whole left subtree
      todo.push_back({item.slot + 1, -1});  // left: next in the array
    }
  }
  m_wide.reserve(m_nodes.size() / 2 + 1);
  collapse(m_wide, 0);
  if (n >= options.wide8_min_primitives) {
    m_wide8.reserve(m_nodes.size() / 4 + 1);
    collapse(m_wide8, 0);
  }
}

template <int W>
std::uint32_t Bvh::collapse(std::vector<BvhWideNode<W>>& out, std::uint32_t binary_index) const {
  // Gather up to W subtrees under this node by repeatedly opening the interior candidate with
  // the largest surface area (the one most likely to be entered), then recurse.
  std::uint32_t candidates[W];
  int n = 0;
  const BvhNode& b = m_nodes[binary_index];
  if (b.count > 0) {
    candidates[n++] = binary_index;  // the whole tree is one leaf
  } else {
    candidates[n++] = binary_index + 1;
    candidates[n++] = b.offset;
  }
  while (n < W) {
    int best = -1;
    float best_area = -1.0f;
    for (int i = 0; i < n; ++i) {
      const BvhNode& c = m_nodes[candidates[i]];
      if (c.count > 0) continue;
      Aabb box;
      box.lo = c.lo;
      box.hi = c.hi;
      if (box.area() > best_area) {
        best_area = box.area();
        best = i;
      }
    }
    if (best < 0) break;
    const std::uint32_t open = candidates[best];
    candidates[best] = open + 1;
    candidates[n++] = m_nodes[open].offset;
  }
  const auto index = static_cast<std::uint32_t>(out.size());
  out.emplace_back();
  for (int i = 0; i < W; ++i) {
    float lo[3] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
                   std::numeric_limits<float>::infinity()};
    float hi[3] = {-lo[0], -lo[1], -lo[2]};
    std::uint32_t child = 0, count = 0;
    if (i < n) {
      const BvhNode& c = m_nodes[candidates[i]];
      for (int k = 0; k < 3; ++k) {
        lo[k] = c.lo[k];
        hi[k] = c.hi[k];
      }
      if (c.count > 0) {
        child = c.offset;
        count = c.count;
      } else {
        child = collapse(out, candidates[i]);  // may reallocate `out`: index, not reference
      }
    }
    BvhWideNode<W>& w = out[index];
    for (int k = 0; k < 3; ++k) {
      w.planes[2 * k][i] = lo[k];
      w.planes[2 * k + 1][i] = hi[k];
    }
    w.child[i] = child;
    w.count[i] = count;
  }
  return index;
}

}  // namespace thaw::render
