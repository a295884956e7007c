#include "breastfit/spatial/detail/leaf_blocks.h"

#include <algorithm>
#include <cstring>
#include <limits>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "breastfit/spatial/detail/parallel_for.h"

namespace breastfit::spatial::detail {
namespace {

/// The largest block: a full leaf with three distinct corners per triangle, in doubles.
constexpr std::size_t kMaxBlockLines = (kLeafHeaderBytes + 24 * 3 * kMaxLeafSize + 63) / 64;
/// Nodes per chunk of the parallel passes and vertices per chunk of the float test (fixed: the
/// blocks do not depend on the threads).
constexpr std::size_t kNodeChunk = 8192;
constexpr std::size_t kVertexChunk = 65536;
/// How many slots ahead of the leaf being built its faces' corner indices and the corners'
/// coordinates are fetched: the faces in Morton order are scattered over the mesh's arrays, and
/// waiting for each in turn would leave the build bound by memory latency.
constexpr std::size_t kFaceLookahead = 64;
constexpr std::size_t kVertexLookahead = 32;

/// A leaf's header (with its corners' slots) and its distinct corners, first-use order.
struct LeafPlan {
  LeafHeader h;
  Index verts[16];  // [0, h.num_vertices)
};
static_assert(3 * kMaxLeafSize <= 16, "a leaf's corners must fit in 16 slots");

/// The distinct vertices of a leaf in first-use order, held in one vector register where there
/// is one (AVX-512: a vertex is compared with all of them at once, without branches or a
/// round trip through memory).
class CornerSet {
 public:
  /// The slot of v, appended when new (`added`).
  int insert(Index v, bool& added) {
#if defined(__AVX512F__)
    const __m512i vv = _mm512_set1_epi32(v);
    const unsigned match = _mm512_cmpeq_epi32_mask(slots_, vv);
    added = match == 0;
    const int slot = added ? size_ : __builtin_ctz(match);
    slots_ = _mm512_mask_mov_epi32(slots_, static_cast<__mmask16>(added ? 1u << size_ : 0u), vv);
    size_ += added ? 1 : 0;
    return slot;
#else
    int slot = 0;
    while (slot < size_ && slots_[slot] != v) ++slot;
    added = slot == size_;
    if (added) slots_[size_++] = v;
    return slot;
#endif
  }
  int size() const { return size_; }
  /// Writes the 16 slots (those past size() are -1).
  void copy_to(Index* out) const {
#if defined(__AVX512F__)
    _mm512_storeu_si512(out, slots_);
#else
    std::copy(slots_, slots_ + 16, out);
#endif
  }

 private:
#if defined(__AVX512F__)
  __m512i slots_ = _mm512_set1_epi32(-1);
#else
  Index slots_[16] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
#endif
  int size_ = 0;
};

/// Plans and writes the blocks of leaves, reading the mesh ahead of the leaf in hand.
class BlockBuilder {
 public:
  BlockBuilder(const TriangleMesh& mesh, const std::vector<std::uint8_t>& face_flags,
               const std::vector<std::uint32_t>& prims, const std::vector<std::uint8_t>& vertex_float)
      : V_(mesh.V.data()),
        F_(mesh.F.data()),
        face_flags_(face_flags.data()),
        prims_(prims.data()),
        num_slots_(prims.size()),
        vertex_float_(vertex_float.data()) {}

  /// Fetches the faces of the slots up to kFaceLookahead past `slot_end` (the end of the leaf
  /// about to be planned) and, with `vertices`, the corners of those up to kVertexLookahead past
  /// it. Called for leaves in slot order (any node range of an LBVH holds its leaves so).
  void look_ahead(std::size_t slot_begin, std::size_t slot_end, bool vertices) {
    if (next_face_ < slot_begin) next_face_ = next_vertex_ = slot_begin;
    for (const std::size_t e = std::min(num_slots_, slot_end + kFaceLookahead); next_face_ < e; ++next_face_)
      __builtin_prefetch(F_ + 3 * static_cast<std::ptrdiff_t>(prims_[next_face_]));
    if (!vertices) return;
    for (const std::size_t e = std::min(num_slots_, slot_end + kVertexLookahead); next_vertex_ < e; ++next_vertex_) {
      const Index* t = F_ + 3 * static_cast<std::ptrdiff_t>(prims_[next_vertex_]);
      for (int k = 0; k < 3; ++k) __builtin_prefetch(V_ + 3 * static_cast<std::ptrdiff_t>(t[k]));
    }
  }

  /// The header and corners of leaf `n`; returns its block's lines.
  std::size_t plan(const BvhNode& n, LeafPlan& p) const {
    std::memset(&p.h, 0, sizeof p.h);  // the header's padding too: blocks are compared as bytes
    CornerSet corners;
    unsigned all_float = 1;  // no new corner so far that is not exactly a float
    for (int t = 0; t < n.count; ++t) {
      const auto f = static_cast<std::int32_t>(prims_[static_cast<std::size_t>(n.first + t)]);
      p.h.face[t] = f;
      p.h.flags[t] = face_flags_[f];
      const Index* tri = F_ + 3 * static_cast<std::ptrdiff_t>(f);
      for (int k = 0; k < 3; ++k) {
        bool added;
        p.h.corner[t][k] = static_cast<std::uint8_t>(corners.insert(tri[k], added));
        all_float &= static_cast<unsigned>(!added) | vertex_float_[tri[k]];  // no branch
      }
    }
    const int nv = corners.size();
    corners.copy_to(p.verts);
    p.h.count = static_cast<std::uint8_t>(n.count);
    p.h.num_vertices = static_cast<std::uint8_t>(nv);
    p.h.float_coords = static_cast<std::uint8_t>(all_float);
    return leaf_block_lines(nv, all_float != 0);
  }

  /// Writes planned leaf `n`'s block (`lines` lines) at line `line` of `blocks` and points `n`
  /// at it with its box.
  void write(const LeafPlan& p, std::size_t lines, CacheLine* blocks, std::size_t line, BvhNode& n) const {
    const int nv = p.h.num_vertices;
    double c[9 * kMaxLeafSize];
    double lo[3], hi[3];
    gather_leaf_corners(V_, p.verts, nv, c, lo, hi);
    alignas(64) unsigned char buf[64 * kMaxBlockLines];
    std::memset(buf, 0, sizeof buf);
    std::memcpy(buf, &p.h, sizeof p.h);
    if (p.h.float_coords) {  // exact
      float f[9 * kMaxLeafSize];
      for (int j = 0; j < 3 * nv; ++j) f[j] = static_cast<float>(c[j]);
      std::memcpy(buf + kLeafHeaderBytes, f, sizeof(float) * 3 * static_cast<std::size_t>(nv));
    } else {
      std::memcpy(buf + kLeafHeaderBytes, c, sizeof(double) * 3 * static_cast<std::size_t>(nv));
    }
    for (int k = 0; k < 3; ++k) {
      n.lo[k] = round_down_to_float(lo[k]);
      n.hi[k] = round_up_to_float(hi[k]);
    }
    n.first = static_cast<std::int32_t>(line);
    n.count = static_cast<std::int32_t>(lines);
    for (std::size_t l = 0; l < lines; ++l) std::memcpy(blocks[line + l].bytes, buf + 64 * l, 64);
  }

 private:
  const double* V_;
  const Index* F_;
  const std::uint8_t* face_flags_;
  const std::uint32_t* prims_;
  std::size_t num_slots_;
  const std::uint8_t* vertex_float_;
  std::size_t next_face_ = 0;    // first slot whose face is not fetched yet
  std::size_t next_vertex_ = 0;  // first slot whose corners are not fetched yet
};

/// 1 for each vertex whose coordinates are all exactly floats, else 0.
std::vector<std::uint8_t> float_vertices(const TriangleMesh& mesh, int threads) {
  const auto nv = static_cast<std::size_t>(mesh.num_vertices());
  std::vector<std::uint8_t> out(nv);
  const double* V = mesh.V.data();
  parallel_for_chunks(nv, kVertexChunk, threads, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t v = b; v < e; ++v) {
      bool exact = true;
      for (int k = 0; k < 3; ++k) {
        const double x = V[3 * v + static_cast<std::size_t>(k)];
        exact = exact && static_cast<double>(static_cast<float>(x)) == x;
      }
      out[v] = exact ? 1 : 0;
    }
  });
  return out;
}

}  // namespace

LeafBlocks build_leaf_blocks(const TriangleMesh& mesh, const std::vector<std::uint8_t>& face_flags,
                             const std::vector<std::uint32_t>& prims, BvhNodes& nodes, int threads) {
  LeafBlocks blocks;
  const std::vector<std::uint8_t> vertex_float = float_vertices(mesh, threads);
  const std::size_t chunks = chunk_count(nodes.size(), kNodeChunk);
  auto is_leaf = [&](std::size_t i) { return i != 1 && nodes[i].is_leaf(); };  // nodes[1]: padding
  // Writes the blocks of the leaves among nodes [b, e) from line `line` on; returns the line after them.
  auto write_blocks = [&](std::size_t b, std::size_t e, std::size_t line) {
    BlockBuilder builder(mesh, face_flags, prims, vertex_float);
    LeafPlan p;
    for (std::size_t i = b; i < e; ++i) {
      if (!is_leaf(i)) continue;
      BvhNode& n = nodes[i];
      builder.look_ahead(static_cast<std::size_t>(n.first), static_cast<std::size_t>(n.first + n.count), true);
      const std::size_t lines = builder.plan(n, p);
      builder.write(p, lines, blocks.data(), line, n);
      line += lines;
    }
    return line;
  };
  if (threads <= 1 || chunks <= 1) {
    // One pass in node order. Upper bound: every leaf full with 3 distinct corners per triangle.
    // The buffer is not initialised, so this only claims address space; lines are written (and
    // paged in) once, in order.
    std::size_t max_lines = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (is_leaf(i)) max_lines += leaf_block_lines(3 * nodes[i].count, false);
    blocks.resize(max_lines);
    blocks.resize(write_blocks(0, nodes.size(), 0));  // shrinks in place
    return blocks;
  }
  // Two passes over fixed chunks of nodes: the lines of each chunk's blocks, then (at offsets
  // from their prefix sums) the blocks.
  std::vector<std::size_t> start(chunks + 1, 0);
  parallel_for_chunks(nodes.size(), kNodeChunk, threads, [&](std::size_t c, std::size_t b, std::size_t e) {
    BlockBuilder builder(mesh, face_flags, prims, vertex_float);
    LeafPlan p;
    std::size_t lines = 0;
    for (std::size_t i = b; i < e; ++i) {
      if (!is_leaf(i)) continue;
      const BvhNode& n = nodes[i];
      builder.look_ahead(static_cast<std::size_t>(n.first), static_cast<std::size_t>(n.first + n.count), false);
      lines += builder.plan(n, p);
    }
    start[c + 1] = lines;
  });
  for (std::size_t c = 0; c < chunks; ++c) start[c + 1] += start[c];
  blocks.resize(start.back());  // uninitialised: every line is written below
  parallel_for_chunks(nodes.size(), kNodeChunk, threads,
                      [&](std::size_t c, std::size_t b, std::size_t e) { write_blocks(b, e, start[c]); });
  return blocks;
}

}  // namespace breastfit::spatial::detail
