#include "breastfit/spatial/detail/bvh.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include "breastfit/spatial/detail/parallel_for.h"
#include "breastfit/spatial/detail/radix_sort.h"

namespace breastfit::spatial::detail {
namespace {

/// Beyond this depth the build switches to object-median splits, which halve the count, so
/// the depth stays below kSahDepthLimit + 32 < kBvhMaxStack.
constexpr int kSahDepthLimit = 64;

struct Aabb {
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity(),
                  -std::numeric_limits<double>::infinity()};
  void grow(const double* l, const double* h) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], l[k]);
      hi[k] = std::max(hi[k], h[k]);
    }
  }
  void grow_point(const double* p) { grow(p, p); }
  double half_area() const {
    const double dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    if (!(dx >= 0.0)) return 0.0;
    return dx * dy + dy * dz + dz * dx;
  }
};

float round_down(double x) { return round_down_to_float(x); }
float round_up(double x) { return round_up_to_float(x); }

struct Task {
  std::int32_t node;
  std::int32_t begin;
  std::int32_t end;
  int depth;
  Aabb box;   // bounds of the primitives' boxes
  Aabb cbox;  // bounds of their centroids
};

struct Bin {
  Aabb box;
  Aabb cbox;
  std::int32_t count = 0;
};

/// LBVH over primitive boxes: sort by the Morton code of the box centres, build the topology
/// (build_morton_topology), then fit the boxes bottom-up.
Bvh build_morton(const std::vector<PrimBox>& boxes, int max_leaf) {
  Bvh bvh;
  const auto n = static_cast<std::int32_t>(boxes.size());
  Aabb cbox;
  for (const PrimBox& b : boxes) {
    const double c[3] = {0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]),
                         0.5 * (b.lo[2] + b.hi[2])};
    cbox.grow_point(c);
  }
  const MortonGrid grid = MortonGrid::over(cbox.lo, cbox.hi);
  std::vector<std::uint64_t> codes(n);
  for (std::int32_t i = 0; i < n; ++i) {
    const double c[3] = {0.5 * (boxes[i].lo[0] + boxes[i].hi[0]),
                         0.5 * (boxes[i].lo[1] + boxes[i].hi[1]),
                         0.5 * (boxes[i].lo[2] + boxes[i].hi[2])};
    codes[i] = grid.code(c);
  }
  const std::vector<std::uint32_t> order = radix_sort_order(codes, 63);
  bvh.prims.assign(order.begin(), order.end());
  bvh.max_depth = build_morton_topology(codes, max_leaf, bvh.nodes);
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    BvhNode& node = bvh.nodes[i];
    if (i == 1 || !node.is_leaf()) continue;  // padding, inner node
    Aabb box;
    for (std::int32_t s = node.first; s < node.first + node.count; ++s) {
      box.grow(boxes[bvh.prims[s]].lo, boxes[bvh.prims[s]].hi);
    }
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = round_down(box.lo[k]);
      node.hi[k] = round_up(box.hi[k]);
    }
  }
  fit_inner_boxes(bvh.nodes);
  return bvh;
}

}  // namespace

namespace {

/// Where the LBVH splits the sorted keys [begin, end) (more than one key): where the highest
/// differing bit flips, or the middle for equal keys.
std::int32_t morton_split(const std::uint64_t* keys, std::int32_t begin, std::int32_t end) {
  const std::uint64_t first = keys[begin], last = keys[end - 1];
  if (first == last) return begin + (end - begin) / 2;
  const int bit = 63 - __builtin_clzll(first ^ last);
  const std::uint64_t mask = std::uint64_t{1} << bit;
  // First key in the range with the bit set (keys sorted, prefix above `bit` shared, the last
  // key has it). Branch-free binary search: the answer stays in [b, b + len).
  const std::uint64_t* b = keys + begin;
  std::size_t len = static_cast<std::size_t>(end - begin);
  while (len > 1) {
    const std::size_t half = len / 2;
    b += (b[half - 1] & mask) ? 0 : half;
    len -= half;
  }
  return static_cast<std::int32_t>(b - keys);
}

struct TopologyRange {
  std::int32_t node, begin, end;
  int depth;
};

/// The serial pre-order build of the subtree over keys [begin, end) whose root is nodes[root]
/// (already allocated). With `defer_above` > 0, a range of at most `defer_above` keys (and more
/// than max_leaf) is not expanded: `on_deferred(range)` is called instead and must append the
/// range's whole subtree (everything the expansion would have appended) to `nodes`. Returns
/// the deepest leaf's depth (deferred subtrees excluded).
template <class OnDeferred>
int topology_preorder(const std::uint64_t* keys, TopologyRange root_range, int max_leaf,
                      BvhNodes& nodes, std::int32_t defer_above, OnDeferred&& on_deferred) {
  int max_depth = 0;
  std::vector<TopologyRange> stack;
  stack.push_back(root_range);
  while (!stack.empty()) {
    const TopologyRange r = stack.back();
    stack.pop_back();
    max_depth = std::max(max_depth, r.depth);
    if (r.end - r.begin <= max_leaf) {
      nodes[r.node].first = r.begin;
      nodes[r.node].count = r.end - r.begin;
      continue;
    }
    if (r.end - r.begin <= defer_above) {
      on_deferred(r);
      continue;
    }
    const std::int32_t mid = morton_split(keys, r.begin, r.end);
    const auto left = static_cast<std::int32_t>(nodes.size());
    nodes.resize(nodes.size() + 2);
    nodes[r.node].first = left;
    nodes[r.node].count = 0;
    stack.push_back({left + 1, mid, r.end, r.depth + 1});
    stack.push_back({left, r.begin, mid, r.depth + 1});
  }
  return max_depth;
}

/// Key ranges up to this size are built as separate subtrees, concurrently (threads > 1).
constexpr std::int32_t kParallelSubtreeKeys = 4096;

}  // namespace

int build_morton_topology(const std::vector<std::uint64_t>& keys, int max_leaf, BvhNodes& nodes,
                          int threads) {
  const auto n = static_cast<std::int32_t>(keys.size());
  max_leaf = std::max(1, max_leaf);
  nodes.clear();
  if (n == 0) return 0;
  // Upper bound on the node count (reserving does not touch the memory).
  nodes.reserve(2 * static_cast<std::size_t>(n) + 2);
  nodes.resize(2);
  const std::uint64_t* k = keys.data();
  auto no_defer = [](const TopologyRange&) {};
  if (threads <= 1 || n <= kParallelSubtreeKeys) return topology_preorder(k, {0, 0, n, 0}, max_leaf, nodes, 0, no_defer);

  // 1. The ranges the top of the tree leaves to subtrees, in pre-order (a dry run of the top).
  std::vector<TopologyRange> deferred;
  {
    BvhNodes top;
    top.resize(2);
    topology_preorder(k, {0, 0, n, 0}, max_leaf, top, kParallelSubtreeKeys,
                      [&](const TopologyRange& r) { deferred.push_back(r); });
  }
  // 2. Each subtree on its own (root at 0, padding at 1, pairs from 2), concurrently.
  std::vector<BvhNodes> sub(deferred.size());
  std::vector<int> sub_depth(deferred.size(), 0);
  parallel_for_chunks(deferred.size(), 1, threads, [&](std::size_t t, std::size_t, std::size_t) {
    const TopologyRange& r = deferred[t];
    sub[t].reserve(2 * static_cast<std::size_t>(r.end - r.begin) + 2);
    sub[t].resize(2);
    sub_depth[t] = topology_preorder(k, {0, r.begin, r.end, r.depth}, max_leaf, sub[t], 0, no_defer);
  });
  // 3. The top again, splicing each subtree in where the serial build would have appended it:
  // the same nodes, at the same indices.
  std::size_t next = 0;
  int max_depth = topology_preorder(k, {0, 0, n, 0}, max_leaf, nodes, kParallelSubtreeKeys,
                                    [&](const TopologyRange& r) {
                                      const BvhNodes& s = sub[next];
                                      const auto base = static_cast<std::int32_t>(nodes.size());
                                      const std::int32_t shift = base - 2;  // local pair 2 → base
                                      auto relocate = [&](BvhNode x) {
                                        if (!x.is_leaf()) x.first += shift;
                                        return x;
                                      };
                                      nodes[r.node] = relocate(s[0]);
                                      nodes.resize(nodes.size() + (s.size() - 2));
                                      for (std::size_t i = 2; i < s.size(); ++i)
                                        nodes[static_cast<std::size_t>(shift) + i] = relocate(s[i]);
                                      ++next;
                                    });
  for (const int d : sub_depth) max_depth = std::max(max_depth, d);
  return max_depth;
}

void fit_inner_boxes(BvhNodes& nodes) {
  for (std::size_t i = nodes.size(); i-- > 0;) {
    if (i == 1) continue;  // padding
    BvhNode& node = nodes[i];
    if (node.is_leaf()) continue;
    const BvhNode& a = nodes[node.first];
    const BvhNode& b = nodes[node.first + 1];
    for (int k = 0; k < 3; ++k) {
      node.lo[k] = std::min(a.lo[k], b.lo[k]);
      node.hi[k] = std::max(a.hi[k], b.hi[k]);
    }
  }
}

Bvh Bvh::build(const std::vector<PrimBox>& boxes, const BvhBuildOptions& options) {
  Bvh bvh;
  const auto n = static_cast<std::int32_t>(boxes.size());
  if (n == 0) return bvh;
  const int max_leaf = std::max(1, options.max_leaf_size);
  if (options.method == BvhBuildMethod::Morton) {
    bvh = build_morton(boxes, max_leaf);
    assert(bvh.max_depth < kBvhMaxStack - 1 && "BVH deeper than the traversal stack");
    return bvh;
  }
  const int num_bins = std::clamp(options.num_bins, 2, 64);

  std::vector<double> centroid(3 * static_cast<std::size_t>(n));
  for (std::int32_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) centroid[3 * i + k] = 0.5 * (boxes[i].lo[k] + boxes[i].hi[k]);
  }
  bvh.prims.resize(n);
  for (std::int32_t i = 0; i < n; ++i) bvh.prims[i] = i;
  bvh.nodes.reserve(2 * static_cast<std::size_t>(n / std::max(1, max_leaf / 2)) + 4);
  bvh.nodes.resize(2);  // root + padding so that child pairs start at an even index

  std::vector<Task> stack;
  {
    Task root{0, 0, n, 0, {}, {}};
    for (std::int32_t i = 0; i < n; ++i) {
      root.box.grow(boxes[i].lo, boxes[i].hi);
      root.cbox.grow_point(&centroid[3 * i]);
    }
    stack.push_back(root);
  }
  std::vector<std::int32_t>& idx = bvh.prims;
  std::vector<Bin> bins(num_bins);
  std::vector<Aabb> right_box(num_bins), right_cbox(num_bins);
  std::vector<std::int32_t> right_count(num_bins);

  while (!stack.empty()) {
    const Task task = stack.back();
    stack.pop_back();
    {
      BvhNode& node = bvh.nodes[task.node];
      for (int k = 0; k < 3; ++k) {
        node.lo[k] = round_down(task.box.lo[k]);
        node.hi[k] = round_up(task.box.hi[k]);
      }
    }
    const std::int32_t count = task.end - task.begin;
    bvh.max_depth = std::max(bvh.max_depth, task.depth);
    if (count <= max_leaf) {
      bvh.nodes[task.node].first = task.begin;
      bvh.nodes[task.node].count = count;
      continue;
    }

    // Binned SAH along the widest centroid axis; the children's bounds come from the bins.
    const Aabb& cbox = task.cbox;
    int axis = 0;
    double ext[3];
    for (int k = 0; k < 3; ++k) ext[k] = cbox.hi[k] - cbox.lo[k];
    if (ext[1] > ext[axis]) axis = 1;
    if (ext[2] > ext[axis]) axis = 2;
    std::int32_t mid = -1;
    Task left_task{0, 0, 0, task.depth + 1, {}, {}};
    Task right_task{0, 0, 0, task.depth + 1, {}, {}};
    if (task.depth < kSahDepthLimit && ext[axis] > 0.0) {
      const double scale = num_bins / ext[axis];
      const double lo = cbox.lo[axis];
      auto bin_of = [&](std::int32_t p) {
        return std::min(num_bins - 1, static_cast<int>((centroid[3 * p + axis] - lo) * scale));
      };
      for (Bin& b : bins) b = Bin{};
      for (std::int32_t s = task.begin; s < task.end; ++s) {
        const std::int32_t p = idx[s];
        Bin& b = bins[bin_of(p)];
        b.count++;
        b.box.grow(boxes[p].lo, boxes[p].hi);
        b.cbox.grow_point(&centroid[3 * p]);
      }
      Aabb acc, cacc;
      std::int32_t acc_n = 0;
      for (int b = num_bins - 1; b > 0; --b) {
        acc.grow(bins[b].box.lo, bins[b].box.hi);
        cacc.grow(bins[b].cbox.lo, bins[b].cbox.hi);
        acc_n += bins[b].count;
        right_box[b] = acc;
        right_cbox[b] = cacc;
        right_count[b] = acc_n;
      }
      acc = Aabb{};
      cacc = Aabb{};
      acc_n = 0;
      double best_cost = std::numeric_limits<double>::infinity();
      int best_split = -1;
      for (int b = 0; b < num_bins - 1; ++b) {
        acc.grow(bins[b].box.lo, bins[b].box.hi);
        cacc.grow(bins[b].cbox.lo, bins[b].cbox.hi);
        acc_n += bins[b].count;
        if (acc_n == 0 || right_count[b + 1] == 0) continue;
        const double cost =
            acc.half_area() * acc_n + right_box[b + 1].half_area() * right_count[b + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best_split = b + 1;
          left_task.box = acc;
          left_task.cbox = cacc;
        }
      }
      if (best_split > 0) {
        right_task.box = right_box[best_split];
        right_task.cbox = right_cbox[best_split];
        auto it = std::partition(idx.begin() + task.begin, idx.begin() + task.end,
                                 [&](std::int32_t p) { return bin_of(p) < best_split; });
        mid = static_cast<std::int32_t>(it - idx.begin());
        if (mid == task.begin || mid == task.end) mid = -1;
      }
    }
    if (mid < 0) {
      // Object median along the widest centroid axis (also handles coincident centroids).
      mid = task.begin + count / 2;
      std::nth_element(idx.begin() + task.begin, idx.begin() + mid, idx.begin() + task.end,
                       [&](std::int32_t a, std::int32_t b) {
                         const double ca = centroid[3 * a + axis], cb = centroid[3 * b + axis];
                         return ca < cb || (ca == cb && a < b);
                       });
      left_task.box = left_task.cbox = right_task.box = right_task.cbox = Aabb{};
      for (std::int32_t s = task.begin; s < task.end; ++s) {
        Task& t = s < mid ? left_task : right_task;
        t.box.grow(boxes[idx[s]].lo, boxes[idx[s]].hi);
        t.cbox.grow_point(&centroid[3 * idx[s]]);
      }
    }
    const auto left = static_cast<std::int32_t>(bvh.nodes.size());
    bvh.nodes.resize(bvh.nodes.size() + 2);
    bvh.nodes[task.node].first = left;
    bvh.nodes[task.node].count = 0;
    left_task.node = left;
    left_task.begin = task.begin;
    left_task.end = mid;
    right_task.node = left + 1;
    right_task.begin = mid;
    right_task.end = task.end;
    stack.push_back(right_task);
    stack.push_back(left_task);
  }
  assert(bvh.max_depth < kBvhMaxStack - 1 && "BVH deeper than the traversal stack");
  return bvh;
}

}  // namespace breastfit::spatial::detail
