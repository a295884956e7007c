#include "breastfit/spatial/closest_point_index.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
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
#include "breastfit/spatial/detail/bvh4_refit.h"
#include "breastfit/spatial/detail/leaf_blocks.h"
#include "breastfit/spatial/detail/parallel_for.h"
#include "breastfit/spatial/detail/point_triangle_kernel.h"
#include "breastfit/spatial/detail/triangle_tables.h"

namespace breastfit::spatial {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using detail::kLeafHeaderBytes;
using detail::kMaxLeafSize;
using detail::LeafHeader;

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
  detail::LeafBlocks blocks;  // see detail/leaf_blocks.h
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
    // Two independent halves, side by side with more than one thread: the faces' flags and the
    // vertex normals; the faces in Morton order and the tree's topology over them. (With one
    // thread in this order, the order of the allocations as before: a build repeated in the
    // process reuses the heap's freed blocks instead of growing it.)
    std::vector<std::uint32_t> prims;
    detail::parallel_invoke(
        threads,
        [&] {
          face_flags = detail::triangle_flags(mesh, &vertex_boundary, threads);
          vertex_normals = mesh::vertex_normals(mesh);
        },
        [&] {
          detail::MortonSorted sorted = detail::triangle_morton_order(mesh, threads);
          detail::build_morton_topology(sorted.codes, kMaxLeafSize, nodes, threads);
          prims = std::move(sorted.prims);
        });
    blocks = detail::build_leaf_blocks(mesh, face_flags, prims, nodes, threads);
    detail::fit_inner_boxes(nodes);
    wide = detail::collapse_to_bvh4(nodes);
    detail::BvhNodes().swap(nodes);  // not needed for queries
  }

  /// `normals`: V's vertex normals, or null to compute them.
  void move_vertices(const Points& V, const Points* normals) {
    mesh.V = V;
    detail::mark_degenerate_faces(mesh, face_flags);
    vertex_normals = normals ? *normals : mesh::vertex_normals(mesh);
    if (!detail::refit_bvh4(mesh, face_flags, blocks, wide)) build(1);  // the same normals again
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
    const double* coords = reinterpret_cast<const double*>(base + kLeafHeaderBytes);
    double widened[9 * kMaxLeafSize];
    if (h->float_coords) {  // exact: the stored floats are the mesh's doubles
      const auto* f = reinterpret_cast<const float*>(base + kLeafHeaderBytes);
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
      const auto* dc = reinterpret_cast<const double*>(base + kLeafHeaderBytes);
      const auto* fc = reinterpret_cast<const float*>(base + kLeafHeaderBytes);
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
      Index verts[3 * kMaxLeafSize];
      detail::leaf_block_vertices(*h, F, verts);
      for (int j = 0; j < h->num_vertices; ++j)
        if (inside & (1u << j)) out.push_back(verts[j]);
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

namespace {

// #V by 3 and finite, as move_vertices needs its arguments (`what`: named in the message).
void check_per_vertex(const Points& P, Index num_vertices, const char* what) {
  if (P.rows() != num_vertices)
    throw InvalidInput(std::string("ClosestPointIndex::move_vertices: ") + std::to_string(P.rows()) + " " + what +
                       " for " + std::to_string(num_vertices) + " vertices");
  if (!P.allFinite()) throw InvalidInput(std::string("ClosestPointIndex::move_vertices: one of the ") + what + " is not finite");
}

}  // namespace

void ClosestPointIndex::move_vertices(const Points& V) {
  check_per_vertex(V, impl_->mesh.num_vertices(), "positions");
  impl_->move_vertices(V, nullptr);
}

void ClosestPointIndex::move_vertices(const Points& V, const Points& normals) {
  check_per_vertex(V, impl_->mesh.num_vertices(), "positions");
  check_per_vertex(normals, impl_->mesh.num_vertices(), "normals");
  impl_->move_vertices(V, &normals);
}

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
