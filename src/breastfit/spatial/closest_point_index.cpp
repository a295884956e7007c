#include "breastfit/spatial/closest_point_index.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "breastfit/core/errors.h"
#include "breastfit/mesh/normals.h"
#include "breastfit/spatial/detail/bvh.h"
#include "breastfit/spatial/detail/bvh4.h"
#include "breastfit/spatial/detail/parallel_for.h"
#include "breastfit/spatial/detail/point_triangle_kernel.h"
#include "breastfit/spatial/detail/triangle_tables.h"

namespace breastfit::spatial {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Leaves hold at most this many triangles (BVH build option).
constexpr int kMaxLeafSize = 4;

/// A leaf's data is one self-contained block of whole 64-byte lines: this header, then the
/// leaf's distinct vertices (3 doubles each, or 3 floats each when every coordinate of the leaf
/// is exactly a float — scans stored in float — which loses nothing and takes half the bytes).
/// Compared with a vertex-index indirection this needs no second memory hop, and compared with
/// 3 corners per triangle it stores shared corners once (the query cost on a large mesh is
/// dominated by cache misses).
struct LeafHeader {
  std::uint8_t count;                        ///< triangles in the leaf
  std::uint8_t num_vertices;                 ///< distinct corners stored after the header
  std::uint8_t float_coords;                 ///< 1: the corners are stored as floats (exact)
  std::uint8_t flags[kMaxLeafSize];          ///< detail::kFlag* per triangle
  std::uint8_t corner[kMaxLeafSize][3];      ///< index into the block's vertices
  std::int32_t face[kMaxLeafSize];           ///< original face index
};
constexpr std::size_t kHeaderBytes = (sizeof(LeafHeader) + 7) / 8 * 8;
struct alignas(64) CacheLine {
  unsigned char bytes[64];
};

/// Running best answer of one query.
struct Best {
  double sq_dist = kInf;
  std::int32_t face = std::numeric_limits<std::int32_t>::max();
  double bary[3] = {0.0, 0.0, 0.0};
  ClosestFeature feature = ClosestFeature::Face;
  bool found = false;

  /// Accepts a candidate when strictly closer, or equally close with a lower face index.
  bool offer(double s, std::int32_t f) const {
    return s < sq_dist || (s == sq_dist && (!found || f < face));
  }
};

/// Lower bounds on the squared distances from q to the four child boxes of a wide node (lane i:
/// child i; an empty slot gives +inf). Float: may overestimate the true values by rounding; the
/// pruning threshold carries a matching slack.
inline void quad_sq_dist(const detail::Bvh4Node& n, const float* q, float out[4]) {
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps();
  __m128 sum = zero;
  for (int k = 0; k < 3; ++k) {
    const __m128 qk = _mm_set1_ps(q[k]);
    const __m128 d = _mm_max_ps(
        _mm_max_ps(_mm_sub_ps(_mm_load_ps(n.lo[k]), qk), _mm_sub_ps(qk, _mm_load_ps(n.hi[k]))), zero);
    sum = _mm_add_ps(sum, _mm_mul_ps(d, d));
  }
  _mm_storeu_ps(out, sum);
#else
  for (int i = 0; i < 4; ++i) {
    float sum = 0.0f;
    for (int k = 0; k < 3; ++k) {
      const float d = std::max(std::max(n.lo[k][i] - q[k], q[k] - n.hi[k][i]), 0.0f);
      sum += d * d;
    }
    out[i] = sum;
  }
#endif
}

}  // namespace

double ClosestPoint::distance() const { return std::sqrt(sq_dist); }

struct ClosestPointIndex::Impl {
  TriangleMesh mesh;
  // Binary tree nodes (during the build only); a leaf's `first` is the index of its block in
  // `blocks` and `count` the number of 64-byte lines of the block.
  detail::BvhNodes nodes;
  // The tree the queries walk: the binary tree collapsed to four children per node (a leaf
  // slot's ref is ~(first line of its block), its count the block's lines).
  detail::Bvh4Nodes wide;
  std::vector<CacheLine, detail::UninitCacheAlignedAllocator<CacheLine>> blocks;
  std::vector<std::uint8_t> face_flags;    // by face: detail::kFlag*
  std::vector<std::uint8_t> vertex_boundary;  // by vertex: 1 on an open-boundary edge
  Points vertex_normals;                   // #V by 3 area-weighted unit normals (or zero)

  /// Builds the tables and the tree (LBVH over the faces' box centres; the same tree as
  /// detail::Bvh::build(detail::triangle_boxes(mesh)) with the Morton method, built without
  /// materialising the boxes: codes come from the mesh, leaf boxes from the leaf blocks).
  Impl(const TriangleMesh& m, int threads) : mesh(m) { build(threads); }
  Impl(TriangleMesh&& m, int threads) : mesh(std::move(m)) { build(threads); }

  void build(int threads) {
    detail::validate_triangle_mesh(mesh, "ClosestPointIndex");
    face_flags = detail::triangle_flags(mesh, &vertex_boundary, threads);
    vertex_normals = mesh::vertex_normals(mesh);
    std::vector<std::uint32_t> prims;
    {
      detail::MortonSorted sorted = detail::triangle_morton_order(mesh, threads);
      detail::build_morton_topology(sorted.codes, kMaxLeafSize, nodes, threads);
      prims = std::move(sorted.prims);
    }
    build_leaf_blocks(prims, threads);
    detail::fit_inner_boxes(nodes);
    wide = detail::collapse_to_bvh4(nodes);
    detail::BvhNodes().swap(nodes);  // not needed for queries
  }

  /// Writes leaf node `n`'s block at lines [line, line + lines) of `blocks` (header `h`, then the
  /// corners `verts[0, nv)`), sets its box (the bounds of those vertices rounded outward to float
  /// = the union of its triangles' boxes) and points the node at the block.
  void write_leaf_block(detail::BvhNode& n, const LeafHeader& h, const Index* verts, int nv,
                        std::size_t line, std::size_t lines) {
    const double* V = mesh.V.data();
    unsigned char* base = blocks[line].bytes;
    std::memset(blocks[line + lines - 1].bytes, 0, 64);  // deterministic padding
    std::memset(base, 0, kHeaderBytes);
    std::memcpy(base, &h, sizeof(LeafHeader));
    auto* coords = reinterpret_cast<double*>(base + kHeaderBytes);
    auto* float_coords = reinterpret_cast<float*>(base + kHeaderBytes);
    double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
    for (int j = 0; j < nv; ++j) {
      const double* p = V + 3 * static_cast<std::ptrdiff_t>(verts[j]);
      for (int k = 0; k < 3; ++k) {
        if (h.float_coords) {
          float_coords[3 * j + k] = static_cast<float>(p[k]);
        } else {
          coords[3 * j + k] = p[k];
        }
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
    for (int k = 0; k < 3; ++k) {
      n.lo[k] = detail::round_down_to_float(lo[k]);
      n.hi[k] = detail::round_up_to_float(hi[k]);
    }
    n.first = static_cast<std::int32_t>(line);
    n.count = static_cast<std::int32_t>(lines);
  }

  /// The header of leaf `n` (slots of `prims`) but its corners.
  LeafHeader leaf_header(const detail::BvhNode& n, const std::vector<std::uint32_t>& prims) const {
    LeafHeader h{};
    h.count = static_cast<std::uint8_t>(n.count);
    for (int t = 0; t < n.count; ++t) {
      const auto f = static_cast<std::int32_t>(prims[static_cast<std::size_t>(n.first + t)]);
      h.face[t] = f;
      h.flags[t] = face_flags[static_cast<std::size_t>(f)];
    }
    return h;
  }

  static std::size_t block_lines(int num_vertices, bool float_coords) {
    const std::size_t bytes_per_vertex = float_coords ? 12 : 24;
    return (kHeaderBytes + bytes_per_vertex * static_cast<std::size_t>(num_vertices) + 63) / 64;
  }

  /// Whether every coordinate of the vertices verts[0, nv) is exactly a float.
  bool float_exact(const Index* verts, int nv) const {
    const double* V = mesh.V.data();
    for (int j = 0; j < nv; ++j) {
      const double* p = V + 3 * static_cast<std::ptrdiff_t>(verts[j]);
      for (int k = 0; k < 3; ++k) {
        if (static_cast<double>(static_cast<float>(p[k])) != p[k]) return false;
      }
    }
    return true;
  }

  /// Replaces each leaf's slot range by its block (see LeafHeader) and sets its box. A leaf's
  /// distinct corners are in first-use order. One thread: one pass in node order, corners
  /// deduplicated with a per-vertex stamp. More: two passes over chunks of leaves, the blocks'
  /// sizes and then (at offsets from their prefix sums) the blocks, corners deduplicated within
  /// the leaf. Both give the same bytes.
  void build_leaf_blocks(const std::vector<std::uint32_t>& prims, int threads) {
    if (threads <= 1) {
      build_leaf_blocks_serial(prims);
      return;
    }
    std::vector<std::int32_t> leaves;
    leaves.reserve(nodes.size() / 2 + 1);
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (i != 1 && nodes[i].is_leaf()) leaves.push_back(static_cast<std::int32_t>(i));
    constexpr std::size_t kLeafChunk = 2048;
    // Distinct corners of a leaf's triangles in first-use order, their number returned.
    const Index* F = mesh.F.data();
    auto corners = [&](const detail::BvhNode& n, Index* verts, LeafHeader* h) {
      int nv = 0;
      for (int t = 0; t < n.count; ++t) {
        const auto f = static_cast<std::ptrdiff_t>(prims[static_cast<std::size_t>(n.first + t)]);
        for (int k = 0; k < 3; ++k) {
          const Index v = F[3 * f + k];
          int slot = 0;
          while (slot < nv && verts[slot] != v) ++slot;
          if (slot == nv) verts[nv++] = v;
          if (h) h->corner[t][k] = static_cast<std::uint8_t>(slot);
        }
      }
      return nv;
    };
    std::vector<std::size_t> start(leaves.size() + 1, 0);
    detail::parallel_for_chunks(leaves.size(), kLeafChunk, threads, [&](std::size_t, std::size_t b, std::size_t e) {
      Index verts[3 * kMaxLeafSize];
      for (std::size_t l = b; l < e; ++l) {
        const int nv = corners(nodes[static_cast<std::size_t>(leaves[l])], verts, nullptr);
        start[l + 1] = block_lines(nv, float_exact(verts, nv));
      }
    });
    for (std::size_t l = 0; l < leaves.size(); ++l) start[l + 1] += start[l];
    blocks.resize(start.back());  // uninitialised: every line is written below
    detail::parallel_for_chunks(leaves.size(), kLeafChunk, threads, [&](std::size_t, std::size_t b, std::size_t e) {
      Index verts[3 * kMaxLeafSize];
      for (std::size_t l = b; l < e; ++l) {
        detail::BvhNode& n = nodes[static_cast<std::size_t>(leaves[l])];
        LeafHeader h = leaf_header(n, prims);
        const int nv = corners(n, verts, &h);
        h.num_vertices = static_cast<std::uint8_t>(nv);
        h.float_coords = float_exact(verts, nv) ? 1 : 0;
        write_leaf_block(n, h, verts, nv, start[l], start[l + 1] - start[l]);
      }
    });
  }

  void build_leaf_blocks_serial(const std::vector<std::uint32_t>& prims) {
    // Upper bound: every leaf full with 3 distinct corners per triangle. The buffer is not
    // initialised, so this only claims address space; lines are written (and paged in) once,
    // in order.
    std::size_t max_lines = 0;
    for (const detail::BvhNode& n : nodes) {
      if (n.is_leaf()) max_lines += block_lines(3 * n.count, false);
    }
    blocks.resize(max_lines);
    std::size_t used = 0;
    const Index* F = mesh.F.data();
    // Distinct corners of a leaf, in first-use order: seen[v] = (leaf number << 4) | slot of
    // v in the current leaf's block (leaf numbers start at 1, so 0 is "not seen").
    static_assert(3 * kMaxLeafSize <= 16, "corner slots must fit in 4 bits");
    std::vector<std::uint32_t> seen(static_cast<std::size_t>(mesh.num_vertices()), 0);
    std::uint32_t leaf_number = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      detail::BvhNode& n = nodes[i];
      if (i == 1 || !n.is_leaf()) continue;  // padding, inner node
      if (++leaf_number >= (1u << 28)) {  // stamps would overflow: start over
        std::fill(seen.begin(), seen.end(), 0u);
        leaf_number = 1;
      }
      LeafHeader h = leaf_header(n, prims);
      Index verts[3 * kMaxLeafSize];
      int nv = 0;
      for (int t = 0; t < n.count; ++t) {
        const Index f = h.face[t];
        for (int k = 0; k < 3; ++k) {
          const Index v = F[3 * static_cast<std::ptrdiff_t>(f) + k];
          std::uint32_t& s = seen[static_cast<std::size_t>(v)];
          if ((s >> 4) != leaf_number) {
            s = (leaf_number << 4) | static_cast<std::uint32_t>(nv);
            verts[nv++] = v;
          }
          h.corner[t][k] = static_cast<std::uint8_t>(s & 15u);
        }
      }
      h.num_vertices = static_cast<std::uint8_t>(nv);
      h.float_coords = float_exact(verts, nv) ? 1 : 0;
      const std::size_t lines = block_lines(nv, h.float_coords != 0);
      write_leaf_block(n, h, verts, nv, used, lines);
      used += lines;
    }
    blocks.resize(used);  // shrinks in place
  }

  const double* vertex(Index face, int corner) const {
    return mesh.V.data() + 3 * static_cast<std::ptrdiff_t>(mesh.F(face, corner));
  }

  /// Tests one face by index (warm start).
  void offer_face(const double* q, Index f, Best& best) const {
    double bary[3];
    ClosestFeature feature;
    const double s = detail::closest_point_on_triangle_kernel(
        q, vertex(f, 0), vertex(f, 1), vertex(f, 2), (face_flags[f] & detail::kFlagDegenerate) != 0,
        bary, feature);
    if (best.offer(s, f)) {
      best.sq_dist = s;
      best.face = f;
      best.found = true;
      std::copy(bary, bary + 3, best.bary);
      best.feature = feature;
    }
  }

  /// Tests the triangles of the leaf block starting at `line`.
  void search_leaf(const double* q, std::int32_t line, Best& best, float& thr,
                   double slack) const {
    const unsigned char* base = blocks[static_cast<std::size_t>(line)].bytes;
    const auto* h = reinterpret_cast<const LeafHeader*>(base);
    const double* coords = reinterpret_cast<const double*>(base + kHeaderBytes);
    double widened[9 * kMaxLeafSize];
    if (h->float_coords) {  // exact: the stored floats are the mesh's doubles
      const auto* f = reinterpret_cast<const float*>(base + kHeaderBytes);
      for (int j = 0; j < 3 * h->num_vertices; ++j) widened[j] = f[j];
      coords = widened;
    }
    for (int i = 0; i < h->count; ++i) {
      double bary[3];
      ClosestFeature feature;
      const double s = detail::closest_point_on_triangle_kernel(
          q, coords + 3 * h->corner[i][0], coords + 3 * h->corner[i][1],
          coords + 3 * h->corner[i][2], (h->flags[i] & detail::kFlagDegenerate) != 0, bary,
          feature);
      if (best.offer(s, h->face[i])) {
        best.sq_dist = s;
        best.face = h->face[i];
        best.found = true;
        std::copy(bary, bary + 3, best.bary);
        best.feature = feature;
        thr = threshold(s, slack);
      }
    }
  }

  /// The float pruning threshold for a best squared distance `sq` (see docs/SPATIAL.md
  /// "Exactness"): a box is skipped only when it provably cannot hold a triangle at least as
  /// close.
  static float threshold(double sq, double slack) {
    if (!(sq < kInf)) return std::numeric_limits<float>::infinity();
    const double r = std::sqrt(sq) + slack;
    return static_cast<float>(r * r * (1.0 + 1e-5));
  }

  /// Branch-and-bound descent of the four-wide tree: visits every child whose box may hold a
  /// triangle at least as close as the current best (nearest first), so the answer is exact.
  void search(const double* q, Best& best) const {
    if (wide.empty()) return;
    const detail::Bvh4Node* nodes = wide.data();
    const float qf[3] = {static_cast<float>(q[0]), static_cast<float>(q[1]),
                         static_cast<float>(q[2])};
    // Box distances are computed in float from a rounded query: allow for both errors.
    const double qmax = std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2]), 1.0});
    const double slack = 4e-7 * qmax;
    float thr = threshold(best.sq_dist, slack);

    struct Entry {
      std::int32_t ref;
      float sq;
    };
    // Start fetching what a child will read (memory-level parallelism: on a large mesh the
    // queries are bound by cache misses, not arithmetic).
    auto prefetch = [&](std::int32_t ref, std::int32_t lines) {
      if (ref < 0) {
        const unsigned char* p = blocks[static_cast<std::size_t>(~ref)].bytes;
        for (std::int32_t l = 0; l < lines; ++l) __builtin_prefetch(p + 64 * l);
      } else {
        __builtin_prefetch(nodes + ref);
        __builtin_prefetch(reinterpret_cast<const unsigned char*>(nodes + ref) + 64);
      }
    };
    Entry stack[detail::kBvh4MaxStack];
    int sp = 0;
    std::int32_t ref = 0;  // the root
    for (;;) {
      if (ref >= 0) {
        const detail::Bvh4Node& n = nodes[ref];
        float d[4];
        quad_sq_dist(n, qf, d);
        // The children within the threshold, nearest first (insertion sort; ties keep slot
        // order). Empty slots are last and never taken.
        int slot[4];
        int m = 0;
        for (int i = 0; i < 4 && n.ref[i] != detail::kBvh4Empty; ++i) {
          if (!(d[i] <= thr)) continue;
          int j = m++;
          while (j > 0 && d[slot[j - 1]] > d[i]) {
            slot[j] = slot[j - 1];
            --j;
          }
          slot[j] = i;
        }
        if (m > 0) {
          for (int j = m - 1; j > 0; --j) {  // farthest pushed first, popped last
            const int i = slot[j];
            prefetch(n.ref[i], n.count[i]);
            stack[sp++] = {n.ref[i], d[i]};
          }
          ref = n.ref[slot[0]];
          prefetch(ref, n.count[slot[0]]);
          continue;
        }
      } else {
        search_leaf(q, ~ref, best, thr, slack);
      }
      // Pop the next child that may still hold a closer triangle.
      for (;;) {
        if (sp == 0) return;
        const Entry& e = stack[--sp];
        if (e.sq <= thr) {
          ref = e.ref;
          break;
        }
      }
    }
  }

  /// Appends the vertices of the leaves within reach whose corners lie within sqrt(r2) of q
  /// (a vertex once per leaf holding it, so possibly several times).
  void collect_vertices(const double* q, double r2, std::vector<Index>& out) const {
    if (wide.empty()) return;
    const detail::Bvh4Node* nodes = wide.data();
    const float qf[3] = {static_cast<float>(q[0]), static_cast<float>(q[1]),
                         static_cast<float>(q[2])};
    const double qmax = std::max({std::abs(q[0]), std::abs(q[1]), std::abs(q[2]), 1.0});
    const float thr = threshold(r2, 4e-7 * qmax);  // as search(): conservative in float
    const Index* F = mesh.F.data();
    std::int32_t stack[detail::kBvh4MaxStack];
    int sp = 0;
    stack[sp++] = 0;
    while (sp > 0) {
      const std::int32_t ref = stack[--sp];
      if (ref >= 0) {
        const detail::Bvh4Node& n = nodes[ref];
        float d[4];
        quad_sq_dist(n, qf, d);
        for (int i = 3; i >= 0; --i)  // slot 0 popped first
          if (n.ref[i] != detail::kBvh4Empty && d[i] <= thr) stack[sp++] = n.ref[i];
        continue;
      }
      const unsigned char* base = blocks[static_cast<std::size_t>(~ref)].bytes;
      const auto* h = reinterpret_cast<const LeafHeader*>(base);
      const auto* dc = reinterpret_cast<const double*>(base + kHeaderBytes);
      const auto* fc = reinterpret_cast<const float*>(base + kHeaderBytes);
      std::uint32_t inside = 0;  // bit j: corner slot j within reach
      for (int j = 0; j < h->num_vertices; ++j) {
        double s = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double c = h->float_coords ? static_cast<double>(fc[3 * j + k]) : dc[3 * j + k];
          const double diff = c - q[k];
          s += diff * diff;
        }
        if (s <= r2) inside |= 1u << j;
      }
      if (inside == 0) continue;
      // Slots are numbered in first-use order over (triangle, corner): the vertex of slot j is
      // the corner where it first appears.
      int next = 0;
      for (int t = 0; t < h->count; ++t)
        for (int k = 0; k < 3; ++k)
          if (h->corner[t][k] == next) {
            if (inside & (1u << next)) out.push_back(F[3 * static_cast<std::ptrdiff_t>(h->face[t]) + k]);
            ++next;
          }
    }
  }

  ClosestPoint finish(const Best& best) const {
    ClosestPoint cp;
    cp.face = best.face;
    cp.bary = Vec3(best.bary[0], best.bary[1], best.bary[2]);
    const double* a = vertex(best.face, 0);
    const double* b = vertex(best.face, 1);
    const double* c = vertex(best.face, 2);
    for (int k = 0; k < 3; ++k) {
      cp.point[k] = best.bary[0] * a[k] + best.bary[1] * b[k] + best.bary[2] * c[k];
    }
    cp.sq_dist = best.sq_dist;
    cp.feature = best.feature;
    cp.on_boundary = detail::feature_on_boundary(best.feature, face_flags[best.face],
                                                 mesh.F(best.face, 0), mesh.F(best.face, 1),
                                                 mesh.F(best.face, 2), vertex_boundary);
    return cp;
  }

  void check_query(const Vec3& q) const {
    if (!q.allFinite()) throw InvalidInput("ClosestPointIndex: query point is not finite");
  }
};

ClosestPointIndex::ClosestPointIndex(const TriangleMesh& mesh, int threads)
    : impl_(std::make_unique<Impl>(mesh, threads)) {}
ClosestPointIndex::ClosestPointIndex(TriangleMesh&& mesh, int threads)
    : impl_(std::make_unique<Impl>(std::move(mesh), threads)) {}
ClosestPointIndex::~ClosestPointIndex() = default;
ClosestPointIndex::ClosestPointIndex(ClosestPointIndex&&) noexcept = default;
ClosestPointIndex& ClosestPointIndex::operator=(ClosestPointIndex&&) noexcept = default;

ClosestPoint ClosestPointIndex::closest(const Vec3& q) const {
  impl_->check_query(q);
  Best best;
  impl_->search(q.data(), best);
  return impl_->finish(best);
}

ClosestPoint ClosestPointIndex::closest(const Vec3& q, Index hint_face) const {
  impl_->check_query(q);
  Best best;
  if (hint_face >= 0 && hint_face < impl_->mesh.num_faces()) {
    impl_->offer_face(q.data(), hint_face, best);
  }
  impl_->search(q.data(), best);
  return impl_->finish(best);
}

std::optional<ClosestPoint> ClosestPointIndex::closest_within(const Vec3& q,
                                                              double max_dist) const {
  impl_->check_query(q);
  if (std::isnan(max_dist) || max_dist < 0.0) {
    throw InvalidInput("ClosestPointIndex::closest_within: max_dist must be >= 0, got " +
                       std::to_string(max_dist));
  }
  Best best;
  best.sq_dist = max_dist * max_dist;
  impl_->search(q.data(), best);
  if (!best.found) return std::nullopt;
  return impl_->finish(best);
}

std::optional<ClosestPoint> ClosestPointIndex::closest_within(const Vec3& q, double max_dist,
                                                              Index hint_face) const {
  impl_->check_query(q);
  if (std::isnan(max_dist) || max_dist < 0.0) {
    throw InvalidInput("ClosestPointIndex::closest_within: max_dist must be >= 0, got " +
                       std::to_string(max_dist));
  }
  Best best;
  best.sq_dist = max_dist * max_dist;
  if (hint_face >= 0 && hint_face < impl_->mesh.num_faces()) {
    impl_->offer_face(q.data(), hint_face, best);
  }
  impl_->search(q.data(), best);
  if (!best.found) return std::nullopt;
  return impl_->finish(best);
}

std::vector<ClosestPoint> ClosestPointIndex::closest_batch(const Points& Q) const {
  const auto n = static_cast<std::size_t>(Q.rows());
  std::vector<ClosestPoint> out(n);
  if (n == 0) return out;
  if (!Q.allFinite()) throw InvalidInput("ClosestPointIndex::closest_batch: non-finite query");
  const std::vector<std::uint32_t> order = query_order(Q);
  Index hint = -1;
  for (const std::uint32_t i : order) {
    const double* q = Q.data() + 3 * static_cast<std::ptrdiff_t>(i);
    Best best;
    if (hint >= 0) impl_->offer_face(q, hint, best);
    impl_->search(q, best);
    out[i] = impl_->finish(best);
    hint = best.face;
  }
  return out;
}

void ClosestPointIndex::vertices_within(const Vec3& q, double radius, std::vector<Index>& out) const {
  impl_->check_query(q);
  if (!(radius >= 0.0) || !std::isfinite(radius)) {
    throw InvalidInput("ClosestPointIndex::vertices_within: radius must be finite and >= 0, got " +
                       std::to_string(radius));
  }
  out.clear();
  impl_->collect_vertices(q.data(), radius * radius, out);
  // Each vertex once, by index: a bitmap over the vertices when the ball holds many of them
  // (linear in the vertices / 64), else sorting what was collected.
  const auto nv = static_cast<std::size_t>(impl_->mesh.num_vertices());
  if (out.size() * 64 < nv) {
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return;
  }
  std::vector<std::uint64_t> seen((nv + 63) / 64, 0);
  for (const Index v : out) seen[static_cast<std::size_t>(v) >> 6] |= std::uint64_t{1} << (v & 63);
  out.clear();
  for (std::size_t w = 0; w < seen.size(); ++w)
    for (std::uint64_t bits = seen[w]; bits != 0; bits &= bits - 1)
      out.push_back(static_cast<Index>(64 * w + static_cast<std::size_t>(__builtin_ctzll(bits))));
}

Vec3 ClosestPointIndex::face_normal(Index face) const {
  if (face < 0 || face >= impl_->mesh.num_faces()) {
    throw InvalidInput("ClosestPointIndex::face_normal: face " + std::to_string(face) +
                       " out of range [0, " + std::to_string(impl_->mesh.num_faces()) + ")");
  }
  if (impl_->face_flags[face] & detail::kFlagDegenerate) return Vec3::Zero();
  const Vec3 a = impl_->mesh.V.row(impl_->mesh.F(face, 0));
  const Vec3 b = impl_->mesh.V.row(impl_->mesh.F(face, 1));
  const Vec3 c = impl_->mesh.V.row(impl_->mesh.F(face, 2));
  const Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

Vec3 ClosestPointIndex::smooth_normal(const ClosestPoint& cp) const {
  if (cp.face < 0 || cp.face >= impl_->mesh.num_faces()) {
    throw InvalidInput("ClosestPointIndex::smooth_normal: face " + std::to_string(cp.face) +
                       " out of range");
  }
  Vec3 n = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    n += cp.bary[k] * impl_->vertex_normals.row(impl_->mesh.F(cp.face, k)).transpose();
  }
  const double len = n.norm();
  if (len > 0.0 && std::isfinite(len)) return n / len;
  return face_normal(cp.face);
}

const TriangleMesh& ClosestPointIndex::mesh() const { return impl_->mesh; }

const Points& ClosestPointIndex::vertex_normals() const { return impl_->vertex_normals; }

std::vector<std::uint32_t> query_order(const Points& Q) {
  if (!Q.allFinite()) throw InvalidInput("spatial::query_order: non-finite query");
  return detail::morton_order(Q);
}

}  // namespace breastfit::spatial
