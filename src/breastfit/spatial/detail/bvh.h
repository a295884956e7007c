#pragma once
/// \file Bounding-volume hierarchy over primitive boxes, shared by ClosestPointIndex and
/// RayCaster (private to the spatial layer). Binary tree built by Morton codes (LBVH) or binned
/// SAH, float boxes rounded outward (conservative), children of a node stored as an adjacent
/// pair at an even index so that a pair fills one 64-byte cache line.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
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

/// CacheAlignedAllocator whose value-less construct() default-initialises: resize() leaves
/// trivial elements uninitialised (for buffers that are written right after, e.g. leaf blocks).
template <class T>
struct UninitCacheAlignedAllocator : CacheAlignedAllocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UninitCacheAlignedAllocator<U>;
  };
  UninitCacheAlignedAllocator() = default;
  template <class U>
  UninitCacheAlignedAllocator(const UninitCacheAlignedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(noexcept(::new(static_cast<void*>(p)) U)) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(static_cast<Args&&>(args)...);
  }
  template <class U>
  bool operator==(const UninitCacheAlignedAllocator<U>&) const noexcept { return true; }
};

using BvhNodes = std::vector<BvhNode, CacheAlignedAllocator<BvhNode>>;

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
  BvhNodes nodes;
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

/// The quantisation of the LBVH build: primitive centres (box centres) → 21-bit cells per
/// axis over the centres' bounding box → 63-bit Morton code (x in the highest bit of each
/// triple).
struct MortonGrid {
  double lo[3] = {0.0, 0.0, 0.0};     ///< lower corner of the centres' bounds
  double scale[3] = {0.0, 0.0, 0.0};  ///< cells per unit length (0 on a flat axis)

  /// The grid over centres bounded by [lo, hi] (per axis, lo <= hi).
  static MortonGrid over(const double* lo, const double* hi) {
    MortonGrid g;
    for (int k = 0; k < 3; ++k) {
      const double ext = hi[k] - lo[k];
      g.lo[k] = lo[k];
      g.scale[k] = ext > 0.0 ? static_cast<double>((1u << 21) - 1) / ext : 0.0;
    }
    return g;
  }
  /// Morton code of centre c (inside the bounds).
  std::uint64_t code(const double* c) const {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const auto cell = static_cast<std::uint64_t>((c[k] - lo[k]) * scale[k]);
      code |= spread_bits_21(cell) << (2 - k);
    }
    return code;
  }
};

/// LBVH topology over primitives already sorted by Morton code (`sorted_codes`, ascending):
/// each range is split where its highest differing bit flips (equal codes: halved) until it
/// has at most `max_leaf` primitives. Fills `nodes` (root at 0, padding at 1, child pairs
/// after their parent, pre-order); a leaf's first/count is its range of sorted slots. Boxes
/// are left unset: the caller sets the leaves' and then calls fit_inner_boxes(). Returns the
/// depth of the deepest leaf (at most 63 bit levels plus log2(n) halvings); no keys give no
/// nodes. Used by Bvh::build (Morton) and by ClosestPointIndex, which computes its codes and
/// leaf boxes straight from the mesh. With `threads` > 1 the subtrees below a few thousand keys
/// are built concurrently and spliced in place: the same nodes at the same indices as serially.
int build_morton_topology(const std::vector<std::uint64_t>& sorted_codes, int max_leaf,
                          BvhNodes& nodes, int threads = 1);

/// Sets every inner node's box to the union of its children's (leaves must be set already;
/// children always follow their parent, so one backwards sweep suffices).
void fit_inner_boxes(BvhNodes& nodes);

/// Largest float <= x (x not NaN): outward rounding of a box's lower corner. Same value as
/// std::nextafter on the nearest float when that one is above x, without the libm call.
inline float round_down_to_float(double x) {
  const auto f = static_cast<float>(x);
  if (!(static_cast<double>(f) > x)) return f;
  if (f == 0.0f) return -std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits - 1 : bits + 1);  // +inf → FLT_MAX
}
/// Smallest float >= x (x not NaN): outward rounding of a box's upper corner.
inline float round_up_to_float(double x) {
  const auto f = static_cast<float>(x);
  if (!(static_cast<double>(f) < x)) return f;
  if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
  const auto bits = std::bit_cast<std::uint32_t>(f);
  return std::bit_cast<float>(f > 0.0f ? bits + 1 : bits - 1);  // -inf → -FLT_MAX
}

}  // namespace breastfit::spatial::detail
