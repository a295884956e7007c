#include "breastfit/spatial/detail/triangle_tables.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "breastfit/core/errors.h"
#include "breastfit/spatial/detail/point_triangle_kernel.h"

namespace breastfit::spatial::detail {

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

std::vector<std::uint8_t> triangle_flags(const TriangleMesh& mesh,
                                         std::vector<std::uint8_t>* vertex_boundary) {
  const Index nf = mesh.num_faces();
  const Index nv = mesh.num_vertices();
  std::vector<std::uint8_t> flags(nf, 0);
  const double* V = mesh.V.data();
  for (Index f = 0; f < nf; ++f) {
    if (is_degenerate_triangle(V + 3 * static_cast<std::ptrdiff_t>(mesh.F(f, 0)),
                               V + 3 * static_cast<std::ptrdiff_t>(mesh.F(f, 1)),
                               V + 3 * static_cast<std::ptrdiff_t>(mesh.F(f, 2)))) {
      flags[f] |= kFlagDegenerate;
    }
  }
  // Undirected edges bucketed by their smaller vertex (counting sort), then counted within a
  // bucket: linear time, no hashing.
  std::vector<std::int32_t> start(static_cast<std::size_t>(nv) + 1, 0);
  for (Index f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index u = mesh.F(f, k), w = mesh.F(f, (k + 1) % 3);
      start[std::min(u, w) + 1]++;
    }
  }
  std::partial_sum(start.begin(), start.end(), start.begin());
  struct HalfEdge {
    Index other;
    Index face;
    int corner;
  };
  std::vector<HalfEdge> edges(3 * static_cast<std::size_t>(nf));
  std::vector<std::int32_t> fill(start.begin(), start.end() - 1);
  for (Index f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const Index u = mesh.F(f, k), w = mesh.F(f, (k + 1) % 3);
      edges[fill[std::min(u, w)]++] = {std::max(u, w), f, k};
    }
  }
  if (vertex_boundary != nullptr) vertex_boundary->assign(nv, 0);
  static constexpr std::uint8_t kEdgeBit[3] = {kFlagBoundaryEdge01, kFlagBoundaryEdge12,
                                               kFlagBoundaryEdge20};
  for (Index u = 0; u < nv; ++u) {
    auto b = edges.begin() + start[u], e = edges.begin() + start[u + 1];
    std::sort(b, e, [](const HalfEdge& x, const HalfEdge& y) { return x.other < y.other; });
    for (auto it = b; it != e;) {
      auto run = it + 1;
      while (run != e && run->other == it->other) ++run;
      if (run - it == 1 && it->other != u) {
        flags[it->face] |= kEdgeBit[it->corner];
        if (vertex_boundary != nullptr) {
          (*vertex_boundary)[u] = 1;
          (*vertex_boundary)[it->other] = 1;
        }
      }
      it = run;
    }
  }
  return flags;
}

Points area_weighted_vertex_normals(const TriangleMesh& mesh) {
  Points N = Points::Zero(mesh.num_vertices(), 3);
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    const Vec3 a = mesh.V.row(mesh.F(f, 0));
    const Vec3 b = mesh.V.row(mesh.F(f, 1));
    const Vec3 c = mesh.V.row(mesh.F(f, 2));
    const Vec3 n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) N.row(mesh.F(f, k)) += n.transpose();
  }
  for (Index v = 0; v < N.rows(); ++v) {
    const double len = N.row(v).norm();
    if (len > 0.0 && std::isfinite(len)) {
      N.row(v) /= len;
    } else {
      N.row(v).setZero();
    }
  }
  return N;
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
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  if (n < 2) return order;
  const Vec3 lo = P.colwise().minCoeff();
  const Vec3 hi = P.colwise().maxCoeff();
  const double ext = std::max((hi - lo).maxCoeff(), 1e-300);
  const double scale = static_cast<double>((1u << 21) - 1) / ext;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t code = 0;
    for (int k = 0; k < 3; ++k) {
      const auto cell = static_cast<std::uint64_t>((P(static_cast<Index>(i), k) - lo[k]) * scale);
      code |= spread_bits_21(cell) << k;
    }
    keys[i] = {code, static_cast<std::uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].second;
  return order;
}

}  // namespace breastfit::spatial::detail
