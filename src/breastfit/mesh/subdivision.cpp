#include "breastfit/mesh/subdivision.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "breastfit/core/errors.h"

namespace breastfit::mesh {
namespace {

struct HalfEdge {
  std::uint64_t key;  // (min << 32) | max
  Index face;
  int corner;         // edge from corner k to corner k+1
};

std::uint64_t edge_key(Index a, Index b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

}  // namespace

TriangleMesh subdivide(const TriangleMesh& mesh, bool loop) {
  const Index nv = mesh.num_vertices();
  const Index nf = mesh.num_faces();
  for (Index f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) < 0 || mesh.F(f, k) >= nv)
        throw InvalidInput("subdivide: face " + std::to_string(f) + " has a vertex index out of range");

  std::vector<HalfEdge> he;
  he.reserve(static_cast<size_t>(3 * nf));
  for (Index f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) he.push_back({edge_key(mesh.F(f, k), mesh.F(f, (k + 1) % 3)), f, k});
  std::sort(he.begin(), he.end(), [](const HalfEdge& a, const HalfEdge& b) {
    return a.key != b.key ? a.key < b.key : (a.face != b.face ? a.face < b.face : a.corner < b.corner);
  });

  // Undirected edges: endpoints, opposite vertices, number of incident triangles.
  std::vector<Index> he_edge(static_cast<size_t>(3 * nf));
  std::vector<std::array<Index, 2>> ends;
  std::vector<std::array<Index, 2>> opp;
  std::vector<int> count;
  for (size_t i = 0; i < he.size(); ++i) {
    if (i == 0 || he[i].key != he[i - 1].key) {
      ends.push_back({static_cast<Index>(he[i].key >> 32), static_cast<Index>(he[i].key & 0xffffffffu)});
      opp.push_back({-1, -1});
      count.push_back(0);
    }
    const Index e = static_cast<Index>(ends.size() - 1);
    he_edge[static_cast<size_t>(3 * he[i].face + he[i].corner)] = e;
    if (count[e] < 2) opp[e][count[e]] = mesh.F(he[i].face, (he[i].corner + 2) % 3);
    ++count[e];
  }
  const Index ne = static_cast<Index>(ends.size());

  TriangleMesh out;
  out.V.resize(nv + ne, 3);
  // Edge points.
  for (Index e = 0; e < ne; ++e) {
    const auto [a, b] = ends[e];
    if (loop && count[e] == 2) {
      out.V.row(nv + e) = 0.375 * (mesh.V.row(a) + mesh.V.row(b)) + 0.125 * (mesh.V.row(opp[e][0]) + mesh.V.row(opp[e][1]));
    } else {
      out.V.row(nv + e) = 0.5 * (mesh.V.row(a) + mesh.V.row(b));
    }
  }
  // Vertex points.
  if (!loop) {
    out.V.topRows(nv) = mesh.V;
  } else {
    std::vector<Vec3> sum(static_cast<size_t>(nv), Vec3::Zero()), bsum(static_cast<size_t>(nv), Vec3::Zero());
    std::vector<int> valence(static_cast<size_t>(nv), 0), bcount(static_cast<size_t>(nv), 0);
    std::vector<bool> irregular(static_cast<size_t>(nv), false);
    for (Index e = 0; e < ne; ++e) {
      const auto [a, b] = ends[e];
      const Vec3 pa = mesh.V.row(a).transpose(), pb = mesh.V.row(b).transpose();
      sum[a] += pb;
      sum[b] += pa;
      ++valence[a];
      ++valence[b];
      if (count[e] == 1) {
        bsum[a] += pb;
        bsum[b] += pa;
        ++bcount[a];
        ++bcount[b];
      } else if (count[e] > 2) {
        irregular[a] = irregular[b] = true;
      }
    }
    for (Index v = 0; v < nv; ++v) {
      const Vec3 p = mesh.V.row(v).transpose();
      Vec3 q = p;
      if (irregular[v] || valence[v] == 0) {
        q = p;
      } else if (bcount[v] == 2) {
        q = 0.75 * p + 0.125 * bsum[v];
      } else if (bcount[v] == 0) {
        const int n = valence[v];
        const double beta = n == 3 ? 3.0 / 16.0 : 3.0 / (8.0 * n);
        q = (1.0 - n * beta) * p + beta * sum[v];
      }  // other boundary configurations (pinched): keep
      out.V.row(v) = q.transpose();
    }
  }
  // Faces.
  out.F.resize(4 * nf, 3);
  for (Index f = 0; f < nf; ++f) {
    const Index v0 = mesh.F(f, 0), v1 = mesh.F(f, 1), v2 = mesh.F(f, 2);
    const Index m01 = nv + he_edge[static_cast<size_t>(3 * f + 0)];
    const Index m12 = nv + he_edge[static_cast<size_t>(3 * f + 1)];
    const Index m20 = nv + he_edge[static_cast<size_t>(3 * f + 2)];
    out.F.row(4 * f + 0) << v0, m01, m20;
    out.F.row(4 * f + 1) << v1, m12, m01;
    out.F.row(4 * f + 2) << v2, m20, m12;
    out.F.row(4 * f + 3) << m01, m12, m20;
  }
  return out;
}

SurfacePoint refine_surface_point(const SurfacePoint& p) {
  const double b0 = p.bary[0], b1 = p.bary[1], b2 = p.bary[2];
  SurfacePoint q;
  if (b0 >= 0.5) {
    q.face = 4 * p.face + 0;
    q.bary = Vec3(2 * b0 - 1, 2 * b1, 2 * b2);
  } else if (b1 >= 0.5) {
    q.face = 4 * p.face + 1;
    q.bary = Vec3(2 * b1 - 1, 2 * b2, 2 * b0);
  } else if (b2 >= 0.5) {
    q.face = 4 * p.face + 2;
    q.bary = Vec3(2 * b2 - 1, 2 * b0, 2 * b1);
  } else {
    q.face = 4 * p.face + 3;
    q.bary = Vec3(1 - 2 * b2, 1 - 2 * b0, 1 - 2 * b1);
  }
  return q;
}

double median_edge_length(const TriangleMesh& mesh) {
  const Index nf = mesh.num_faces();
  if (nf == 0) return 0.0;
  std::vector<double> len;
  len.reserve(static_cast<size_t>(3 * nf));
  for (Index f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      len.push_back((mesh.V.row(mesh.F(f, k)) - mesh.V.row(mesh.F(f, (k + 1) % 3))).norm());
  auto mid = len.begin() + static_cast<std::ptrdiff_t>(len.size() / 2);
  std::nth_element(len.begin(), mid, len.end());
  return *mid;
}

}  // namespace breastfit::mesh
