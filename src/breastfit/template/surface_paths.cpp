#include "breastfit/template/surface_paths.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/adjacency.h"

namespace breastfit::templ {
namespace {

using EdgeKey = std::pair<Index, Index>;
EdgeKey key(Index a, Index b) { return {std::min(a, b), std::max(a, b)}; }

Vec3 bary_of(const TriangleMesh& m, Index f, Index a, Index b, double t_from_a) {
  Vec3 w = Vec3::Zero();
  for (int c = 0; c < 3; ++c) {
    if (m.F(f, c) == a) w[c] += 1.0 - t_from_a;
    if (m.F(f, c) == b) w[c] += t_from_a;
  }
  return w;
}

}  // namespace

Vec3 segment_point(const TriangleMesh& mesh, const PathSegment& s, double t) {
  const Vec3 w = (1.0 - t) * s.bary0 + t * s.bary1;
  Vec3 p = Vec3::Zero();
  for (int c = 0; c < 3; ++c) p += w[c] * mesh.V.row(mesh.F(s.face, c)).transpose();
  return p;
}

double path_length(const TriangleMesh& mesh, const SurfacePath& path) {
  double L = 0;
  for (const auto& s : path.segments) L += (segment_point(mesh, s, 1) - segment_point(mesh, s, 0)).norm();
  return L;
}

SurfacePath reversed(const SurfacePath& path) {
  SurfacePath r;
  r.closed = path.closed;
  for (auto it = path.segments.rbegin(); it != path.segments.rend(); ++it)
    r.segments.push_back({it->face, it->bary1, it->bary0});
  return r;
}

SurfacePath rotated_to_start_near(const TriangleMesh& mesh, const SurfacePath& path, const Vec3& p) {
  if (!path.closed || path.segments.empty()) return path;
  size_t best = 0;
  double bd = 1e300;
  for (size_t i = 0; i < path.segments.size(); ++i) {
    const double d = (segment_point(mesh, path.segments[i], 0) - p).squaredNorm();
    if (d < bd) { bd = d; best = i; }
  }
  SurfacePath r;
  r.closed = true;
  for (size_t i = 0; i < path.segments.size(); ++i)
    r.segments.push_back(path.segments[(best + i) % path.segments.size()]);
  return r;
}

std::vector<SurfacePath> iso_lines(const TriangleMesh& mesh, const Eigen::VectorXd& scalar, double level) {
  if (scalar.size() != mesh.num_vertices()) throw InvalidInput("iso_lines: one scalar per vertex needed");
  auto above = [&](Index v) { return scalar[v] >= level; };
  // Crossing edges of each crossing face and the faces of each crossing edge.
  std::map<EdgeKey, std::vector<Index>> edge_faces;
  std::vector<std::vector<EdgeKey>> face_edges(mesh.num_faces());
  for (Index f = 0; f < mesh.num_faces(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const Index a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
      if (above(a) != above(b)) {
        face_edges[f].push_back(key(a, b));
        edge_faces[key(a, b)].push_back(f);
      }
    }
  }
  auto t_on = [&](const EdgeKey& e) {  // fraction from e.first to e.second
    const double sa = scalar[e.first] - level, sb = scalar[e.second] - level;
    return sa / (sa - sb);
  };
  std::vector<char> used(mesh.num_faces(), 0);
  std::vector<SurfacePath> out;
  auto walk = [&](EdgeKey e, Index f, bool closed) {
    SurfacePath p;
    p.closed = closed;
    const EdgeKey start = e;
    while (f >= 0 && !used[f] && face_edges[f].size() == 2) {
      used[f] = 1;
      const EdgeKey e2 = face_edges[f][0] == e ? face_edges[f][1] : face_edges[f][0];
      p.segments.push_back({f, bary_of(mesh, f, e.first, e.second, t_on(e)),
                            bary_of(mesh, f, e2.first, e2.second, t_on(e2))});
      e = e2;
      if (closed && e == start) break;
      const auto& fs = edge_faces[e];
      Index next = -1;
      for (Index g : fs)
        if (g != f) next = g;
      f = next;
    }
    if (!p.segments.empty()) out.push_back(std::move(p));
  };
  // Open paths first: start at crossing edges with a single face (on the mesh boundary).
  for (const auto& [e, fs] : edge_faces)
    if (fs.size() == 1 && !used[fs[0]]) walk(e, fs[0], false);
  for (Index f = 0; f < mesh.num_faces(); ++f)
    if (!used[f] && face_edges[f].size() == 2) walk(face_edges[f][0], f, true);
  return out;
}

SurfacePath edge_path(const TriangleMesh& mesh, const std::vector<Index>& vertices) {
  SurfacePath p;
  const mesh::AdjacencyLists faces_of = mesh::vertex_faces(mesh);
  auto in_range = [&](Index v) { return v >= 0 && v < mesh.num_vertices(); };
  for (size_t i = 0; i + 1 < vertices.size(); ++i) {
    const Index a = vertices[i], b = vertices[i + 1];
    Index face = -1;  // the lowest triangle with both a and b
    if (in_range(a) && in_range(b))
      for (const Index f : faces_of[a])
        if (mesh.F(f, 0) == b || mesh.F(f, 1) == b || mesh.F(f, 2) == b) {
          face = f;
          break;
        }
    if (face < 0)
      throw InvalidInput("edge_path: vertices " + std::to_string(a) + " and " + std::to_string(b) +
                         " share no edge");
    p.segments.push_back({face, bary_of(mesh, face, a, b, 0.0), bary_of(mesh, face, a, b, 1.0)});
  }
  return p;
}

std::vector<SurfacePoint> resample_path(const TriangleMesh& mesh, const SurfacePath& path, double spacing) {
  if (!(spacing > 0)) throw InvalidInput("resample_path: spacing must be > 0");
  if (path.segments.empty()) throw InvalidInput("resample_path: empty path");
  std::vector<double> len;
  double total = 0;
  for (const auto& s : path.segments) {
    len.push_back((segment_point(mesh, s, 1) - segment_point(mesh, s, 0)).norm());
    total += len.back();
  }
  const int n = std::max(path.closed ? 3 : 1, static_cast<int>(std::lround(total / spacing)));
  const double step = total / n;
  const int count = path.closed ? n : n + 1;
  std::vector<SurfacePoint> out;
  size_t seg = 0;
  double acc = 0;  // arc length at the start of segment `seg`
  for (int k = 0; k < count; ++k) {
    const double s = std::min(k * step, total);
    while (seg + 1 < len.size() && acc + len[seg] < s) {
      acc += len[seg];
      ++seg;
    }
    const double t = len[seg] > 1e-12 ? std::clamp((s - acc) / len[seg], 0.0, 1.0) : 0.0;
    const auto& S = path.segments[seg];
    SurfacePoint sp;
    sp.face = S.face;
    sp.bary = (1.0 - t) * S.bary0 + t * S.bary1;
    sp.bary /= sp.bary.sum();
    out.push_back(sp);
  }
  return out;
}

}  // namespace breastfit::templ
