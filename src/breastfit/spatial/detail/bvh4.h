#pragma once
/// \file Four-wide BVH for closest-point queries (private to the spatial layer): a binary tree
/// from detail/bvh collapsed so that every node holds up to four child boxes side by side
/// (structure of arrays), tested against a query at once with SIMD. Half the depth of the
/// binary tree, so a query pops and pushes half as often; the boxes are the binary tree's own
/// (float, rounded outward), so pruning stays conservative.
#include <cstdint>
#include <vector>

#include "breastfit/spatial/detail/bvh.h"

namespace breastfit::spatial::detail {

/// One node: 128 bytes (two cache lines). Child slot i is empty when ref[i] == kBvh4Empty,
/// a leaf when ref[i] < 0 (its payload index is ~ref[i], with `count[i]` as the binary leaf's
/// count), else an inner node (index into Bvh4::nodes). Empty slots come last.
struct alignas(64) Bvh4Node {
  float lo[3][4];  ///< lo[axis][child]
  float hi[3][4];  ///< hi[axis][child]
  std::int32_t ref[4];
  std::int32_t count[4];
};
static_assert(sizeof(Bvh4Node) == 128, "Bvh4Node must stay 128 bytes");

inline constexpr std::int32_t kBvh4Empty = INT32_MIN;

/// Largest traversal stack a Bvh4 needs (three entries per level at most, depth < 64).
inline constexpr int kBvh4MaxStack = 3 * 64 + 4;

using Bvh4Nodes = std::vector<Bvh4Node, CacheAlignedAllocator<Bvh4Node>>;

/// Collapses a binary tree (detail::Bvh layout: root at 0, padding at 1, boxes fitted) into a
/// four-wide one: a node's children are its binary children, each inner one replaced by its
/// own two children (so 2–4 per node, binary child order kept), nodes in depth-first pre-order.
/// A binary leaf becomes a child slot with ref = ~first and count = count. The root is
/// nodes[0]; a binary tree that is a single leaf gives one node with one slot. An empty
/// binary tree gives no nodes.
Bvh4Nodes collapse_to_bvh4(const BvhNodes& binary);

}  // namespace breastfit::spatial::detail
