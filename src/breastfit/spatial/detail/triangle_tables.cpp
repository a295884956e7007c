#include "breastfit/spatial/detail/triangle_tables.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <utility>

#include "breastfit/core/errors.h"
#include "breastfit/spatial/detail/parallel_for.h"
#include "breastfit/spatial/detail/point_triangle_kernel.h"
#include "breastfit/spatial/detail/radix_sort.h"

namespace breastfit::spatial::detail {
namespace {

/// Faces per chunk of the parallel loops (fixed: the tables do not depend on the threads).
constexpr std::size_t kFaceChunk = 16384;

}  // namespace

void validate_triangle_mesh(const TriangleMesh& mesh, const std::string& who) {
  if (mesh.num_faces() == 0) throw InvalidInput(who + ": the mesh has no triangles");
  if (!mesh.V.allFinite()) throw InvalidInput(who + ": the mesh has non-finite vertices");
  const Index nv = mesh.num_vertices();
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index v = mesh.F(f, k);
      if (v < 0 || v >= nv) {
        throw InvalidInput(who + ": face " + std::to_string(f) + " uses vertex " +
                           std::to_string(v) + ", out of range [0, " + std::to_string(nv) + ")");
      }
    }
  }
}

void mark_degenerate_faces(const TriangleMesh& mesh, std::vector<std::uint8_t>& flags, int threads) {
  const double* V = mesh.V.data();
  parallel_for_chunks(static_cast<std::size_t>(mesh.num_faces()), kFaceChunk, threads,
                      [&](std::size_t, std::size_t b, std::size_t e) {
                        for (auto f = static_cast<Index>(b); f < static_cast<Index>(e); ++f) {
                          const bool degenerate = is_degenerate_triangle(V + 3 * static_cast<std::ptrdiff_t>(mesh.F(f, 0)),
                                                                         V + 3 * static_cast<std::ptrdiff_t>(mesh.F(f, 1)),
                                                                         V + 3 * static_cast<std::ptrdiff_t>(mesh.F(f, 2)));
                          flags[f] = static_cast<std::uint8_t>((flags[f] & ~kFlagDegenerate) |
                                                               (degenerate ? kFlagDegenerate : 0));
                        }
                      });
}

std::vector<std::uint8_t> triangle_flags(const TriangleMesh& mesh,
                                         std::vector<std::uint8_t>* vertex_boundary, int threads) {
  const Index nf = mesh.num_faces();
  const Index nv = mesh.num_vertices();
  std::vector<std::uint8_t> flags(nf, 0);
  mark_degenerate_faces(mesh, flags, threads);
  // Undirected edges bucketed by their smaller vertex (counting sort), then counted within a
  // bucket with a per-vertex stamp: linear time, no hashing, no sorting.
  const Index* F = mesh.F.data();  // row-major #F by 3
  const std::size_t nh = 3 * static_cast<std::size_t>(nf);
  // end[u]: first the bucket sizes, then (prefix sums) where bucket u starts, and after the
  // fill where it ends; bucket u is [u > 0 ? end[u - 1] : 0, end[u]).
  std::vector<std::uint32_t> end(static_cast<std::size_t>(nv) + 1, 0);
  for (Index f = 0; f < nf; ++f) {
    const Index* t = F + 3 * static_cast<std::ptrdiff_t>(f);
    end[std::min(t[0], t[1]) + 1]++;
    end[std::min(t[1], t[2]) + 1]++;
    end[std::min(t[2], t[0]) + 1]++;
  }
  std::partial_sum(end.begin(), end.end(), end.begin());
  struct Edge {
    Index other;  // larger vertex (the bucket is the smaller one)
    Index face;
  };
  const std::unique_ptr<Edge[]> edges(new Edge[nh]);  // uninitialised: every slot is filled
  for (Index f = 0; f < nf; ++f) {
    const Index* t = F + 3 * static_cast<std::ptrdiff_t>(f);
    for (int k = 0; k < 3; ++k) {
      const Index u = t[k], w = t[k == 2 ? 0 : k + 1];
      edges[end[std::min(u, w)]++] = {std::max(u, w), f};
    }
  }
  if (vertex_boundary != nullptr) vertex_boundary->assign(nv, 0);
  static constexpr std::uint8_t kEdgeBit[3] = {kFlagBoundaryEdge01, kFlagBoundaryEdge12,
                                               kFlagBoundaryEdge20};
  // While bucket u is counted, stamp[w] is 2u for an edge {u, w} met once so far and 2u + 1
  // for one met again (stale values from other buckets never equal 2u or 2u + 1).
  std::vector<std::uint32_t> stamp(nv, 0xffffffffu);
  std::uint32_t bucket_begin = 0;
  for (Index u = 0; u < nv; ++u) {
    const Edge* b = edges.get() + bucket_begin;
    const Edge* e = edges.get() + end[u];
    bucket_begin = end[u];
    const std::uint32_t once = 2 * static_cast<std::uint32_t>(u);
    for (const Edge* it = b; it != e; ++it) {  // branch-free: first or repeated use
      std::uint32_t& s = stamp[it->other];
      s = (s >> 1) == static_cast<std::uint32_t>(u) ? once + 1 : once;
    }
    for (const Edge* it = b; it != e; ++it) {
      const Index w = it->other;
      if (stamp[w] != once || w == u) continue;
      // An open edge: exactly one face has it, and at exactly one corner.
      const Index* t = F + 3 * static_cast<std::ptrdiff_t>(it->face);
      for (int k = 0; k < 3; ++k) {
        const Index a = t[k], c = t[k == 2 ? 0 : k + 1];
        if (std::min(a, c) == u && std::max(a, c) == w) flags[it->face] |= kEdgeBit[k];
      }
      if (vertex_boundary != nullptr) {
        (*vertex_boundary)[u] = 1;
        (*vertex_boundary)[w] = 1;
      }
    }
  }
  return flags;
}

std::vector<PrimBox> triangle_boxes(const TriangleMesh& mesh) {
  std::vector<PrimBox> boxes(mesh.num_faces());
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    PrimBox& b = boxes[f];
    for (int k = 0; k < 3; ++k) {
      const double x0 = mesh.V(mesh.F(f, 0), k), x1 = mesh.V(mesh.F(f, 1), k),
                   x2 = mesh.V(mesh.F(f, 2), k);
      b.lo[k] = std::min({x0, x1, x2});
      b.hi[k] = std::max({x0, x1, x2});
    }
  }
  return boxes;
}

bool feature_on_boundary(ClosestFeature feature, std::uint8_t flags, Index v0, Index v1,
                         Index v2, const std::vector<std::uint8_t>& vertex_boundary) {
  switch (feature) {
    case ClosestFeature::Face: return false;
    case ClosestFeature::Edge01: return (flags & kFlagBoundaryEdge01) != 0;
    case ClosestFeature::Edge12: return (flags & kFlagBoundaryEdge12) != 0;
    case ClosestFeature::Edge20: return (flags & kFlagBoundaryEdge20) != 0;
    case ClosestFeature::Vertex0: return vertex_boundary[v0] != 0;
    case ClosestFeature::Vertex1: return vertex_boundary[v1] != 0;
    case ClosestFeature::Vertex2: return vertex_boundary[v2] != 0;
  }
  return false;
}


std::vector<std::uint32_t> morton_order(const Points& P) {
  const auto n = static_cast<std::size_t>(P.rows());
  if (n < 2) return std::vector<std::uint32_t>(n, 0u);
  const Vec3 lo = P.colwise().minCoeff();
  const Vec3 hi = P.colwise().maxCoeff();
  const double ext = std::max((hi - lo).maxCoeff(), 1e-300);
  const double scale = static_cast<double>((1u << 21) - 1) / ext;
  std::vector<std::uint64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const auto cell = static_cast<std::uint64_t>((P(static_cast<Index>(i), k) - lo[k]) * scale);
      code |= spread_bits_21(cell) << k;
    }
    keys[i] = code;
  }
  return radix_sort_order(keys, 63);  // stable: ties by row index
}

MortonSorted triangle_morton_order(const TriangleMesh& mesh, int threads) {
  const Index nf = mesh.num_faces();
  const double* V = mesh.V.data();
  const Index* F = mesh.F.data();
  // The centre of the face's box, exactly as 0.5 * (lo + hi) of triangle_boxes().
  auto centre = [&](Index f, double* c) {
    const double* a = V + 3 * static_cast<std::ptrdiff_t>(F[3 * static_cast<std::ptrdiff_t>(f)]);
    const double* b =
        V + 3 * static_cast<std::ptrdiff_t>(F[3 * static_cast<std::ptrdiff_t>(f) + 1]);
    const double* d =
        V + 3 * static_cast<std::ptrdiff_t>(F[3 * static_cast<std::ptrdiff_t>(f) + 2]);
    for (int k = 0; k < 3; ++k) {
      const double lo = std::min({a[k], b[k], d[k]});
      const double hi = std::max({a[k], b[k], d[k]});
      c[k] = 0.5 * (lo + hi);
    }
  };
  constexpr double kInf = std::numeric_limits<double>::infinity();
  // Bounds of the centres per chunk, then over the chunks (min and max are exact: any order).
  const auto n = static_cast<std::size_t>(nf);
  struct Bounds {
    double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf};
  };
  std::vector<Bounds> chunk_bounds(chunk_count(n, kFaceChunk));
  parallel_for_chunks(n, kFaceChunk, threads, [&](std::size_t chunk, std::size_t b, std::size_t e) {
    Bounds& bo = chunk_bounds[chunk];
    for (auto f = static_cast<Index>(b); f < static_cast<Index>(e); ++f) {
      double c[3];
      centre(f, c);
      for (int k = 0; k < 3; ++k) {
        bo.lo[k] = std::min(bo.lo[k], c[k]);
        bo.hi[k] = std::max(bo.hi[k], c[k]);
      }
    }
  });
  Bounds all;
  for (const Bounds& bo : chunk_bounds)
    for (int k = 0; k < 3; ++k) {
      all.lo[k] = std::min(all.lo[k], bo.lo[k]);
      all.hi[k] = std::max(all.hi[k], bo.hi[k]);
    }
  const MortonGrid grid = MortonGrid::over(all.lo, all.hi);
  MortonSorted out;
  out.codes.resize(nf);
  parallel_for_chunks(n, kFaceChunk, threads, [&](std::size_t, std::size_t b, std::size_t e) {
    for (auto f = static_cast<Index>(b); f < static_cast<Index>(e); ++f) {
      double c[3];
      centre(f, c);
      out.codes[f] = grid.code(c);
    }
  });
  out.prims = radix_sort_order(out.codes, 63);
  return out;
}

}  // namespace breastfit::spatial::detail
