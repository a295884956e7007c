#pragma once
/// \file The leaves of ClosestPointIndex's tree as blocks of 64-byte lines (private to the
/// spatial layer): the block layout the queries read and its build from the mesh.
///
/// A leaf's data is one self-contained block of whole lines: a LeafHeader, then the leaf's
/// distinct vertices (3 doubles each, or 3 floats each when every coordinate of the leaf is
/// exactly a float — scans stored in float — which loses nothing and takes half the bytes).
/// Compared with a vertex-index indirection this needs no second memory hop, and compared with
/// 3 corners per triangle it stores shared corners once (the query cost on a large mesh is
/// dominated by cache misses).
#include <algorithm>
#include <cstddef>
#include <limits>
#include <cstdint>
#include <vector>

#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/detail/bvh.h"

namespace breastfit::spatial::detail {

/// Leaves hold at most this many triangles (the LBVH's leaf size).
inline constexpr int kMaxLeafSize = 4;

struct LeafHeader {
  std::uint8_t count;                        ///< triangles in the leaf
  std::uint8_t num_vertices;                 ///< distinct corners stored after the header
  std::uint8_t float_coords;                 ///< 1: the corners are stored as floats (exact)
  std::uint8_t flags[kMaxLeafSize];          ///< detail::kFlag* per triangle
  std::uint8_t corner[kMaxLeafSize][3];      ///< index into the block's vertices
  std::int32_t face[kMaxLeafSize];           ///< original face index
};
/// Where a block's vertices start (the header rounded up to 8 bytes).
inline constexpr std::size_t kLeafHeaderBytes = (sizeof(LeafHeader) + 7) / 8 * 8;

struct alignas(64) CacheLine {
  unsigned char bytes[64];
};
using LeafBlocks = std::vector<CacheLine, UninitCacheAlignedAllocator<CacheLine>>;

/// Lines of a block with `num_vertices` corners, stored as floats or doubles.
inline std::size_t leaf_block_lines(int num_vertices, bool float_coords) {
  const std::size_t bytes_per_vertex = float_coords ? 12 : 24;
  return (kLeafHeaderBytes + bytes_per_vertex * static_cast<std::size_t>(num_vertices) + 63) / 64;
}

/// The vertices of a block's corner slots, in slot order (first use over (triangle, corner), as
/// the build numbers them), from the faces `F` (row-major #F by 3) into out[0, h.num_vertices).
inline void leaf_block_vertices(const LeafHeader& h, const Index* F, Index* out) {
  int next = 0;
  for (int t = 0; t < h.count; ++t)
    for (int k = 0; k < 3; ++k)
      if (h.corner[t][k] == next) out[next++] = F[3 * static_cast<std::ptrdiff_t>(h.face[t]) + k];
}

/// The coordinates of vertices verts[0, nv) of V (row-major #V by 3) into c (3 per vertex) and
/// their bounds into lo/hi: a block's corners and its box before rounding to float.
inline void gather_leaf_corners(const double* V, const Index* verts, int nv, double* c, double lo[3], double hi[3]) {
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::numeric_limits<double>::infinity();
    hi[k] = -std::numeric_limits<double>::infinity();
  }
  for (int j = 0; j < nv; ++j) {
    const double* v = V + 3 * static_cast<std::ptrdiff_t>(verts[j]);
    for (int k = 0; k < 3; ++k) {
      c[3 * j + k] = v[k];
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  }
}

/// The blocks of the leaves of `nodes` (an LBVH over the faces of `mesh`: a leaf's first/count
/// are its slots of `prims`, at most kMaxLeafSize; nodes[1] is padding), in node order. Each
/// leaf is pointed at its block (first = its first line, count = its lines) and given its box:
/// the bounds of its corners rounded outward to float (the union of its triangles' boxes). A
/// block's corners are the leaf's distinct vertices in first-use order (triangle, corner); its
/// bytes after the corners are zero. `face_flags`: detail::kFlag* by face. `threads`: of the
/// build; the blocks and nodes are the same bytes for any number.
LeafBlocks build_leaf_blocks(const TriangleMesh& mesh, const std::vector<std::uint8_t>& face_flags,
                             const std::vector<std::uint32_t>& prims, BvhNodes& nodes, int threads);

}  // namespace breastfit::spatial::detail
