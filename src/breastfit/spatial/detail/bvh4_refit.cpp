#include "breastfit/spatial/detail/bvh4_refit.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "breastfit/spatial/detail/triangle_tables.h"

namespace breastfit::spatial::detail {
namespace {

/// Rewrites the block at `line` with the corners' new positions and the faces' degenerate bits;
/// its box in `lo`/`hi` (doubles, not rounded). False when a float block cannot hold a corner.
bool refit_block(const TriangleMesh& mesh, const std::vector<std::uint8_t>& face_flags, CacheLine* line,
                 double lo[3], double hi[3]) {
  unsigned char* base = line->bytes;
  LeafHeader h;
  std::memcpy(&h, base, sizeof h);
  for (int t = 0; t < h.count; ++t)
    h.flags[t] = static_cast<std::uint8_t>((h.flags[t] & ~kFlagDegenerate) | (face_flags[h.face[t]] & kFlagDegenerate));
  Index verts[3 * kMaxLeafSize];
  leaf_block_vertices(h, mesh.F.data(), verts);
  double c[9 * kMaxLeafSize];
  gather_leaf_corners(mesh.V.data(), verts, h.num_vertices, c, lo, hi);
  const std::size_t n = 3 * static_cast<std::size_t>(h.num_vertices);
  if (h.float_coords) {
    float f[9 * kMaxLeafSize];
    for (std::size_t j = 0; j < n; ++j) {
      f[j] = static_cast<float>(c[j]);
      if (static_cast<double>(f[j]) != c[j]) return false;
    }
    std::memcpy(base + kLeafHeaderBytes, f, sizeof(float) * n);
  } else {
    std::memcpy(base + kLeafHeaderBytes, c, sizeof(double) * n);
  }
  std::memcpy(base, &h, sizeof h);
  return true;
}

}  // namespace

bool refit_bvh4(const TriangleMesh& mesh, const std::vector<std::uint8_t>& face_flags, LeafBlocks& blocks,
                Bvh4Nodes& wide) {
  // Depth-first pre-order: every inner child comes after its parent, so going backwards each
  // node's children are refitted before it reads their boxes.
  for (std::size_t i = wide.size(); i-- > 0;) {
    Bvh4Node& n = wide[i];
    for (int s = 0; s < 4 && n.ref[s] != kBvh4Empty; ++s) {
      if (n.ref[s] < 0) {
        double lo[3], hi[3];
        if (!refit_block(mesh, face_flags, &blocks[static_cast<std::size_t>(~n.ref[s])], lo, hi)) return false;
        for (int k = 0; k < 3; ++k) {
          n.lo[k][s] = round_down_to_float(lo[k]);
          n.hi[k][s] = round_up_to_float(hi[k]);
        }
        continue;
      }
      const Bvh4Node& child = wide[static_cast<std::size_t>(n.ref[s])];
      for (int k = 0; k < 3; ++k) {
        float lo = std::numeric_limits<float>::infinity(), hi = -std::numeric_limits<float>::infinity();
        for (int c = 0; c < 4 && child.ref[c] != kBvh4Empty; ++c) {
          lo = std::min(lo, child.lo[k][c]);
          hi = std::max(hi, child.hi[k][c]);
        }
        n.lo[k][s] = lo;
        n.hi[k][s] = hi;
      }
    }
  }
  return true;
}

}  // namespace breastfit::spatial::detail
