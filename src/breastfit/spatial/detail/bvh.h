#pragma once
/// \file Bounding-volume hierarchy over primitive boxes, shared by ClosestPointIndex and
/// RayCaster (private to the spatial layer). Binary tree built by Morton codes (LBVH) or binned
/// SAH, float boxes rounded outward (conservative), children of a node stored as an adjacent
/// pair at an even index so that a pair fills one 64-byte cache line.
#include <cstddef>
#include <cstdint>
#include <new>
#include <vector>

namespace breastfit::spatial::detail {

/// One node: 32 bytes. A leaf has count > 0 and owns slots [first, first + count) of
/// Bvh::prims; an inner node has count == 0 and children first and first + 1.
struct alignas(32) BvhNode {
  float lo[3];
  std::int32_t first;
  float hi[3];
  std::int32_t count;
  bool is_leaf() const { return count > 0; }
};
static_assert(sizeof(BvhNode) == 32, "BvhNode must stay 32 bytes");

/// Minimal 64-byte aligned allocator (node pairs share one cache line).
template <class T>
struct CacheAlignedAllocator {
  using value_type = T;
  CacheAlignedAllocator() = default;
  template <class U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{64}));
  }
  void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t{64}); }
  template <class U>
  bool operator==(const CacheAlignedAllocator<U>&) const noexcept { return true; }
};

/// Axis-aligned box of one primitive, double precision (input to the build).
struct PrimBox {
  double lo[3];
  double hi[3];
};

/// How the tree is split.
enum class BvhBuildMethod {
  Sah,     ///< binned surface-area heuristic (better trees, ~5x slower build)
  Morton,  ///< centroids sorted on a Morton curve, split at the highest differing bit (LBVH)
};

struct BvhBuildOptions {
  BvhBuildMethod method = BvhBuildMethod::Morton;  ///< see docs/SPATIAL.md for the comparison
  int max_leaf_size = 4;  ///< primitives per leaf at most (>= 1)
  int num_bins = 16;      ///< SAH bins along the widest centroid axis (2..64); Sah only
};

/// The tree. nodes[0] is the root, nodes[1] is unused padding, pairs start at index 2.
struct Bvh {
  std::vector<BvhNode, CacheAlignedAllocator<BvhNode>> nodes;
  std::vector<std::int32_t> prims;  ///< slot → primitive index (leaf order)
  int max_depth = 0;                ///< depth of the deepest leaf (root = 0)

  /// Builds over `boxes` (one per primitive, all finite). An empty input gives an empty tree.
  static Bvh build(const std::vector<PrimBox>& boxes, const BvhBuildOptions& options = {});
};

/// Largest traversal stack any tree from Bvh::build needs (depth is capped during the build).
inline constexpr int kBvhMaxStack = 128;

/// Spreads the low 21 bits of x three apart (bit i → bit 3i): one axis of a 63-bit Morton code.
inline std::uint64_t spread_bits_21(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

}  // namespace breastfit::spatial::detail
