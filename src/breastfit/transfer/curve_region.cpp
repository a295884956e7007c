#include "breastfit/transfer/curve_region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/adjacency.h"
#include "breastfit/mesh/boundary.h"
#include "breastfit/mesh/graph.h"
#include "breastfit/mesh/subdivision.h"
#include "breastfit/spatial/knn_index.h"
#include "breastfit/spatial/point_triangle.h"
#include "breastfit/transfer/polyline.h"
#include "breastfit/transfer/volume_cache.h"

namespace breastfit::transfer {
namespace {

/// Prefix of curve_region's error messages.
constexpr const char* kWho = "vertices_inside_curve";
/// Vertex expansions allowed to join two consecutive snapped samples by an edge path.
constexpr int kMaxPathExpansions = 20000;

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

[[noreturn]] void fail(const std::string& problem) { throw InvalidInput(std::string(kWho) + ": " + problem); }

double mean_edge_length(const Points& V, const Triangles& F) {
  double s = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) s += (V.row(F(f, k)) - V.row(F(f, (k + 1) % 3))).norm();
  return F.rows() ? s / (3.0 * static_cast<double>(F.rows())) : 0.0;
}

/// The mesh with its vertex graph, as the steps of find_region see it.
struct SurfaceGraph {
  const Points& V;
  const Triangles& F;
  Index nv;
  std::shared_ptr<const MeshTopology> topology;
  const mesh::AdjacencyLists& nbr;  ///< neighbours of every vertex
  const mesh::AdjacencyLists& vf;   ///< triangles around every vertex
  double h;                         ///< mean edge length (at least 1e-6)

  SurfaceGraph(const TriangleMesh& mesh, VolumeCache* cache)
      : V(mesh.V),
        F(mesh.F),
        nv(mesh.num_vertices()),
        topology(topology_of(mesh, cache)),
        nbr(topology->neighbours),
        vf(topology->faces),
        h(std::max(mean_edge_length(mesh.V, mesh.F), 1e-6)) {}

  /// Closest point to p on the triangles around vertex v (the surface near v).
  Vec3 closest_on_fan(const Vec3& p, Index v) const {
    Vec3 best = V.row(v);
    double best_d2 = (best - p).squaredNorm();
    for (const Index f : vf[v]) {
      const spatial::PointTriangleResult r =
          spatial::closest_point_on_triangle(p, V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)));
      if (r.sq_dist < best_d2) {
        best_d2 = r.sq_dist;
        best = r.point;
      }
    }
    return best;
  }
};

/// Even-odd point-in-polygon test in 2D.
bool inside_polygon(const Vec2& p, const std::vector<Vec2>& poly) {
  bool in = false;
  const size_t n = poly.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x) in = !in;
    }
  }
  return in;
}

/// Closed curve samples with a grid for nearest-point queries and local tangents.
struct SampledCurve {
  Points S;              ///< #S by 3 samples, closed
  std::unique_ptr<spatial::KnnIndex> grid;  ///< over S
  double spacing = 0;

  /// Nearest point on the polyline near p (through its nearest sample) and the tangent there
  /// (averaged over the two segments at a sample).
  std::pair<Vec3, Vec3> nearest(const Vec3& p) const {
    const Index n = static_cast<Index>(S.rows());
    const Index k = grid->closest(p).index;
    Vec3 best_c = S.row(k);
    double best_d = (best_c - p).squaredNorm();
    const Vec3 t_prev = (S.row(k) - S.row((k + n - 1) % n)).transpose();
    const Vec3 t_next = (S.row((k + 1) % n) - S.row(k)).transpose();
    Vec3 best_t = t_prev.normalized() + t_next.normalized();
    for (int side = 0; side < 2; ++side) {
      const Vec3 a = S.row(side ? k : (k + n - 1) % n), b = S.row(side ? (k + 1) % n : k);
      const Vec3 d = b - a;
      const double dd = d.squaredNorm();
      if (dd <= 0) continue;
      const double t = d.dot(p - a) / dd;
      if (t <= 0 || t >= 1) continue;
      const Vec3 c = a + t * d;
      const double dc = (c - p).squaredNorm();
      if (dc < best_d) {
        best_d = dc;
        best_c = c;
        best_t = d;
      }
    }
    return {best_c, best_t.normalized()};
  }
};

/// The curve's best-fit plane (PCA of its samples) and the curve projected onto it.
struct CurvePlane {
  Vec3 mean = Vec3::Zero();   ///< a point of the plane
  Vec3 e1 = Vec3::UnitX();    ///< first in-plane axis (largest spread)
  Vec3 e2 = Vec3::UnitY();    ///< second in-plane axis
  std::vector<Vec2> polygon;  ///< the curve in (e1, e2) coordinates

  Vec2 project(const Vec3& p) const {
    const Vec3 d = p - mean;
    return Vec2(d.dot(e1), d.dot(e2));
  }
  /// Sets the polygon to the rows of S projected onto the plane.
  void set_polygon(const Points& S) {
    polygon.resize(static_cast<size_t>(S.rows()));
    for (Eigen::Index i = 0; i < S.rows(); ++i) polygon[static_cast<size_t>(i)] = project(S.row(i).transpose());
  }
  /// True when p projects inside the curve.
  bool contains(const Vec3& p) const { return inside_polygon(project(p), polygon); }
};

/// \throws InvalidInput for a mesh without triangles, non-finite coordinates or a bad index.
void check_mesh(const TriangleMesh& mesh) {
  if (mesh.num_faces() == 0) fail("the mesh has no triangles");
  if (!mesh.V.allFinite()) fail("the mesh has non-finite vertex coordinates");
  if (mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= mesh.num_vertices())
    fail("a triangle's vertex index is out of range");
}

/// The curve without repeated consecutive points (nor a repeated first point at the end).
Points distinct_points(const Points& C) {
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < C.rows(); ++i)
    if (keep.empty() || (C.row(i) - C.row(keep.back())).norm() > 1e-9) keep.push_back(i);
  while (keep.size() > 1 && (C.row(keep.back()) - C.row(keep.front())).norm() <= 1e-9) keep.pop_back();
  Points out(static_cast<Eigen::Index>(keep.size()), 3);
  for (size_t i = 0; i < keep.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = C.row(keep[i]);
  return out;
}

}  // namespace

void CurveRegionOptions::validate() const {
  if (!(max_curve_distance_mm > 0) || !std::isfinite(max_curve_distance_mm))
    throw InvalidInput("CurveRegionOptions.max_curve_distance_mm = " + fmt(max_curve_distance_mm) + ": must be > 0");
}

void CurveVolumeOptions::validate() const {
  volume.validate();
  region.validate();
  if (!(target_edge_mm >= 0) || !std::isfinite(target_edge_mm))
    throw InvalidInput("CurveVolumeOptions.target_edge_mm = " + fmt(target_edge_mm) + ": must be >= 0");
  if (max_refined_faces < 1) throw InvalidInput("CurveVolumeOptions.max_refined_faces must be >= 1");
}

namespace {

// ---- the steps of find_region, in order ----------------------------------------------------

/// The input checked (options, mesh, curve) and the curve's distinct points.
Points checked_curve(const TriangleMesh& mesh, const Points& closed_curve_mm, const CurveRegionOptions& options) {
  options.validate();
  check_mesh(mesh);
  if (closed_curve_mm.rows() < 3)
    fail("the curve has " + std::to_string(closed_curve_mm.rows()) + " points (a closed curve needs at least 3)");
  if (!closed_curve_mm.allFinite()) fail("the curve has non-finite coordinates");
  Points C = distinct_points(closed_curve_mm);
  if (C.rows() < 3) fail("the curve has fewer than 3 distinct points");
  return C;
}

/// Samples every half edge (at most 200k of them).
SampledCurve sample_curve(const Points& C, double h) {
  SampledCurve curve;
  curve.spacing = std::max(0.5 * h, polyline_length(C, true) / 200000.0);
  curve.S = resample_polyline(C, true, curve.spacing);
  return curve;
}

/// Best-fit plane (PCA) of the samples S (the polygon is left empty); a collinear curve has no
/// inside.
CurvePlane best_fit_plane(const Points& S) {
  CurvePlane plane;
  plane.mean = S.colwise().mean();
  const Points D = S.rowwise() - plane.mean.transpose();
  Eigen::SelfAdjointEigenSolver<Mat3> eig(D.transpose() * D);
  const Vec3 lam = eig.eigenvalues();  // ascending
  if (!(lam(2) > 0) || lam(1) <= 1e-10 * lam(2)) fail("the curve is degenerate (its points are collinear)");
  plane.e1 = eig.eigenvectors().col(2);
  plane.e2 = eig.eigenvectors().col(1);
  return plane;
}

/// The samples near the surface, each with its foot on the surface and the vertex nearest to it.
struct SnappedCurve {
  std::vector<Index> vertices;  ///< per kept sample: the vertex nearest to its foot
  std::vector<Vec3> feet;       ///< per kept sample: the closest surface point
  double distance_sum = 0;      ///< sum of the sample-to-foot distances
};

/// Snaps every sample to its nearest vertex within `reach` (only vertices near the curve enter
/// the grid) and to its foot: the closest surface point on the triangles around that vertex.
SnappedCurve snap_to_surface(const SurfaceGraph& g, const Points& S, double reach) {
  const Vec3 lo = S.colwise().minCoeff().transpose().array() - reach;
  const Vec3 hi = S.colwise().maxCoeff().transpose().array() + reach;
  std::vector<Index> near_ids;
  for (Index v = 0; v < g.nv; ++v) {
    if (g.nbr.size(v) == 0) continue;
    const Vec3 p = g.V.row(v);
    if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) near_ids.push_back(v);
  }
  Points near_points(static_cast<Eigen::Index>(near_ids.size()), 3);
  for (size_t k = 0; k < near_ids.size(); ++k) near_points.row(static_cast<Eigen::Index>(k)) = g.V.row(near_ids[k]);
  const spatial::KnnIndex vgrid(near_points);
  // The vertex near the curve nearest to p within reach, or -1.
  auto nearest_vertex = [&](const Vec3& p) -> Index {
    if (near_ids.empty()) return -1;
    const spatial::Neighbor nb = vgrid.closest(p);
    return nb.sq_dist <= reach * reach ? near_ids[static_cast<size_t>(nb.index)] : -1;
  };
  SnappedCurve out;
  const Index ns = static_cast<Index>(S.rows());
  for (Index i = 0; i < ns; ++i) {
    const Vec3 p = S.row(i);
    const Index v = nearest_vertex(p);
    if (v < 0) continue;
    const Vec3 foot = g.closest_on_fan(p, v);
    out.distance_sum += (foot - p).norm();
    const Index w = nearest_vertex(foot);
    out.vertices.push_back(w >= 0 ? w : v);
    out.feet.push_back(foot);
  }
  if (2 * out.vertices.size() < static_cast<size_t>(ns))
    fail("most of the curve is more than " + fmt(reach) + " mm from the surface (another frame or units?)");
  return out;
}

/// The snapped vertices on the piece of the mesh most of them are on: samples snapped onto
/// another piece (a floating fragment of a scan) are dropped.
std::vector<Index> on_main_piece(const SurfaceGraph& g, const std::vector<Index>& snapped) {
  std::vector<int> piece(static_cast<size_t>(g.nv), -1);
  std::vector<int> votes;
  for (const Index s0 : snapped) {
    if (piece[static_cast<size_t>(s0)] < 0) {
      mesh::flood_fill(g.nbr, s0, static_cast<int>(votes.size()), piece);
      votes.push_back(0);
    }
    ++votes[static_cast<size_t>(piece[static_cast<size_t>(s0)])];
  }
  const int main_piece = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
  std::vector<Index> kept;
  for (const Index v : snapped)
    if (piece[static_cast<size_t>(v)] == main_piece) kept.push_back(v);
  if (10 * (snapped.size() - kept.size()) > snapped.size()) fail("the curve runs over unconnected parts of the mesh");
  return kept;
}

/// A closed path along mesh edges.
struct EdgeLoop {
  std::vector<Index> vertices;  ///< in order along the curve, each once
  std::vector<char> on_loop;    ///< #V flags
};

/// The closed edge loop through the snapped vertices: consecutive ones joined by shortest edge
/// paths (a sample out of the search budget is skipped).
EdgeLoop closed_edge_loop(const SurfaceGraph& g, const std::vector<Index>& snapped) {
  EdgeLoop loop;
  loop.on_loop.assign(static_cast<size_t>(g.nv), 0);
  auto add = [&](Index v) {
    if (!loop.on_loop[static_cast<size_t>(v)]) {
      loop.on_loop[static_cast<size_t>(v)] = 1;
      loop.vertices.push_back(v);
    }
  };
  mesh::EdgePathFinder paths(g.V, g.nbr);
  add(snapped[0]);
  Index a = snapped[0];
  size_t skipped = 0;
  for (size_t i = 1; i <= snapped.size(); ++i) {
    const Index b = snapped[i % snapped.size()];
    if (a == b) continue;
    if (g.nbr.contains(a, b)) {
      add(b);
      a = b;
      continue;
    }
    const std::vector<Index> path = paths.path(a, b, kMaxPathExpansions);
    if (path.empty()) {  // out of the search budget: a far jump, skip the sample
      ++skipped;
      continue;
    }
    for (const Index v : path) add(v);
    a = b;
  }
  if (a != snapped[0] || 10 * skipped > snapped.size())
    fail("the curve jumps across the surface (no short path along the mesh between its points)");
  return loop;
}

/// Pieces of the surface without the loop: a label per vertex (-1 on the loop and on vertices
/// no triangle uses) and their number.
struct Pieces {
  std::vector<int> label;
  int count = 0;
};

Pieces pieces_without_loop(const SurfaceGraph& g, const EdgeLoop& loop) {
  Pieces pieces;
  pieces.label.assign(static_cast<size_t>(g.nv), -1);
  for (Index s = 0; s < g.nv; ++s) {
    if (loop.on_loop[static_cast<size_t>(s)] || pieces.label[static_cast<size_t>(s)] >= 0 || g.nbr.size(s) == 0)
      continue;
    mesh::flood_fill(g.nbr, s, pieces.count, pieces.label, &loop.on_loop);
    ++pieces.count;
  }
  return pieces;
}

/// Vote: the vertices next to the loop that project inside the curve tell which pieces are in.
/// Returns 1 per vertex of an inside piece (0 on the loop).
std::vector<char> inside_pieces(const SurfaceGraph& g, const EdgeLoop& loop, const Pieces& pieces,
                                const CurvePlane& plane) {
  std::vector<Index> rim;  // non-loop vertices adjacent to the loop, in loop order
  {
    std::vector<char> seen(static_cast<size_t>(g.nv), 0);
    for (const Index u : loop.vertices)
      for (const Index w : g.nbr[u])
        if (!loop.on_loop[static_cast<size_t>(w)] && !seen[static_cast<size_t>(w)]) {
          seen[static_cast<size_t>(w)] = 1;
          rim.push_back(w);
        }
  }
  const auto nc = static_cast<size_t>(pieces.count);
  std::vector<int> pos(nc, 0), neg(nc, 0);
  for (const Index w : rim) (plane.contains(g.V.row(w).transpose()) ? pos : neg)[static_cast<size_t>(pieces.label[static_cast<size_t>(w)])]++;
  std::vector<char> piece_inside(nc, 0);
  bool any_in = false, any_out = false;
  for (size_t c = 0; c < nc; ++c) {
    if (pos[c] + neg[c] == 0) continue;
    piece_inside[c] = pos[c] > neg[c];
    (piece_inside[c] ? any_in : any_out) = true;
  }
  if (any_in && !any_out) fail("the curve does not cut the surface in two (it runs over a gap or around a handle)");
  std::vector<char> inside(static_cast<size_t>(g.nv), 0);
  for (Index v = 0; v < g.nv; ++v) {
    const int c = pieces.label[static_cast<size_t>(v)];
    if (c >= 0) inside[static_cast<size_t>(v)] = piece_inside[static_cast<size_t>(c)];
  }
  return inside;
}

/// The loop's own vertices lie within about half an edge of the curve, on either side of it.
/// Each is classified in the curve's normal plane at its nearest curve point c: the surface
/// crosses that plane along a path from the outside pieces through (near) c to the inside
/// pieces; the vertex is inside when, seen from the surface point q nearest to c, it lies in
/// the direction of its inside neighbours rather than of its outside ones. This holds at sharp
/// folds too (a ptotic breast's underside over the chest), where a normal-based side test fails.
/// Writes the loop vertices' entries of `inside` (read for the other vertices).
void classify_loop_vertices(const SurfaceGraph& g, const SampledCurve& curve, const CurvePlane& plane,
                            const EdgeLoop& loop, const Pieces& pieces, std::vector<char>& inside) {
  std::vector<char> loop_inside(loop.vertices.size(), 0);
  for (size_t i = 0; i < loop.vertices.size(); ++i) {
    const Index v = loop.vertices[i];
    const auto [c, t] = curve.nearest(g.V.row(v).transpose());
    const Vec3 q = g.closest_on_fan(c, v);
    auto across = [&](Index w) {
      const Vec3 d = g.V.row(w).transpose() - q;
      return Vec3(d - t * d.dot(t));
    };
    const Vec3 u = across(v);
    Vec3 a_in = Vec3::Zero(), a_out = Vec3::Zero();
    for (const Index w : g.nbr[v]) {
      if (loop.on_loop[static_cast<size_t>(w)] || pieces.label[static_cast<size_t>(w)] < 0) continue;
      const Vec3 d = across(w);
      if (d.norm() <= 0) continue;
      (inside[static_cast<size_t>(w)] ? a_in : a_out) += d.normalized();
    }
    const double un = u.norm();
    if (un <= 1e-9 * g.h) {
      loop_inside[i] = 0;  // on the curve: a border vertex
    } else if (a_in.norm() > 0 && a_out.norm() > 0) {
      loop_inside[i] = u.dot(a_in.normalized()) > u.dot(a_out.normalized());
    } else if (a_in.norm() > 0) {
      loop_inside[i] = u.dot(a_in) > 0;
    } else if (a_out.norm() > 0) {
      loop_inside[i] = u.dot(a_out) < 0;
    } else {
      loop_inside[i] = plane.contains(g.V.row(v).transpose());
    }
  }
  for (size_t i = 0; i < loop.vertices.size(); ++i) inside[static_cast<size_t>(loop.vertices[i])] = loop_inside[i];
}

/// curve_region; with `border`, also the nearest point of the curve (its feet on the surface)
/// to each loop vertex, in the order of CurveRegion::loop.
CurveRegion find_region(const TriangleMesh& mesh, const Points& closed_curve_mm, const CurveRegionOptions& options,
                        std::vector<Vec3>* border, VolumeCache* cache) {
  const Points C = checked_curve(mesh, closed_curve_mm, options);
  const SurfaceGraph g(mesh, cache);
  SampledCurve curve = sample_curve(C, g.h);
  CurvePlane plane = best_fit_plane(curve.S);
  const SnappedCurve snapped = snap_to_surface(g, curve.S, options.max_curve_distance_mm + 4 * g.h);
  // From here on the curve is its samples' feet on the surface (the closest surface point, on the
  // triangles around the nearest vertex): a curve drawn on a scan lies a few mm off a fit of it,
  // and off the surface its sides would be blurred where the surface is steep.
  curve.S.resize(static_cast<Eigen::Index>(snapped.feet.size()), 3);
  for (size_t i = 0; i < snapped.feet.size(); ++i) curve.S.row(static_cast<Eigen::Index>(i)) = snapped.feet[i].transpose();
  plane.set_polygon(curve.S);
  CurveRegion out;
  out.mean_curve_distance_mm = snapped.distance_sum / static_cast<double>(snapped.vertices.size());
  if (out.mean_curve_distance_mm > options.max_curve_distance_mm)
    fail("the curve is " + fmt(out.mean_curve_distance_mm) + " mm from the surface on average (more than " +
         fmt(options.max_curve_distance_mm) + " mm: another frame or units?)");

  const EdgeLoop loop = closed_edge_loop(g, on_main_piece(g, snapped.vertices));
  const Pieces pieces = pieces_without_loop(g, loop);
  std::vector<char> inside = inside_pieces(g, loop, pieces, plane);
  curve.grid = std::make_unique<spatial::KnnIndex>(curve.S);
  classify_loop_vertices(g, curve, plane, loop, pieces, inside);

  for (Index v = 0; v < g.nv; ++v)
    if (inside[static_cast<size_t>(v)]) out.inside.push_back(v);
  if (out.inside.empty()) fail("the curve encloses no vertex of the mesh");
  out.loop = loop.vertices;
  std::sort(out.loop.begin(), out.loop.end());
  if (border)
    for (const Index v : out.loop) border->push_back(curve.nearest(g.V.row(v).transpose()).first);
  return out;
}

/// The patch under a region: the triangles touching the region ∪ loop grown by `grow` mm along
/// the edges and by one more ring (two rings of triangles around the grown region in all), with
/// the vertices they use renumbered in order.
TriangleMesh patch_around(const TriangleMesh& mesh, const CurveRegion& region, double grow, VolumeCache* cache) {
  const Index nv = mesh.num_vertices();
  const std::shared_ptr<const MeshTopology> topology = topology_of(mesh, cache);
  const mesh::AdjacencyLists& nbr = topology->neighbours;
  std::vector<Index> sources = region.inside;
  sources.insert(sources.end(), region.loop.begin(), region.loop.end());
  const std::vector<double> dist = mesh::edge_distances(mesh.V, nbr, sources, grow);
  // core: the grown region and one ring; the patch's triangles touch it (two rings in all).
  std::vector<char> core(static_cast<size_t>(nv), 0);
  for (Index v = 0; v < nv; ++v)
    if (std::isfinite(dist[static_cast<size_t>(v)])) {
      core[static_cast<size_t>(v)] = 1;
      for (const Index w : nbr[v]) core[static_cast<size_t>(w)] = 1;
    }
  std::vector<Eigen::Index> faces;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    if (core[static_cast<size_t>(mesh.F(f, 0))] || core[static_cast<size_t>(mesh.F(f, 1))] || core[static_cast<size_t>(mesh.F(f, 2))])
      faces.push_back(f);
  std::vector<Index> remap(static_cast<size_t>(nv), -1);
  for (const Eigen::Index f : faces)
    for (int k = 0; k < 3; ++k) remap[static_cast<size_t>(mesh.F(f, k))] = 0;
  Index n_patch = 0;
  for (Index v = 0; v < nv; ++v)
    if (remap[static_cast<size_t>(v)] == 0) remap[static_cast<size_t>(v)] = n_patch++;
  TriangleMesh patch;
  patch.V.resize(n_patch, 3);
  for (Index v = 0; v < nv; ++v)
    if (remap[static_cast<size_t>(v)] >= 0) patch.V.row(remap[static_cast<size_t>(v)]) = mesh.V.row(v);
  patch.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) patch.F(static_cast<Eigen::Index>(i), k) = remap[static_cast<size_t>(mesh.F(faces[i], k))];
  return patch;
}

}  // namespace

CurveRegion curve_region(const TriangleMesh& mesh, const Points& closed_curve_mm, const CurveRegionOptions& options) {
  return find_region(mesh, closed_curve_mm, options, nullptr, nullptr);
}

std::vector<Index> vertices_inside_curve(const TriangleMesh& mesh, const Points& closed_curve_mm,
                                         const CurveRegionOptions& options) {
  return curve_region(mesh, closed_curve_mm, options).inside;
}

namespace {

// Refuses a region whose surface has a hole or an open border inside the curve.
void check_no_hole_inside(const TriangleMesh& mesh, const CurveRegion& region, VolumeCache& cache) {
  const std::vector<bool> inside = [&] {
    std::vector<bool> in(static_cast<size_t>(mesh.num_vertices()), false);
    for (Index v : region.inside) in[static_cast<size_t>(v)] = true;
    for (Index v : region.loop) in[static_cast<size_t>(v)] = false;  // a border along the curve is outside it
    return in;
  }();
  int holes = 0;
  double longest = 0;
  Index border_vertices = 0;
  for (const auto& loop : *cache.boundary_loops(mesh)) {
    const auto n = std::count_if(loop.begin(), loop.end(), [&](Index v) { return inside[static_cast<size_t>(v)]; });
    if (n == 0) continue;
    ++holes;
    border_vertices += static_cast<Index>(n);
    longest = std::max(longest, mesh::loop_length(mesh.V, loop));
  }
  if (holes == 0) return;
  char buf[160];
  std::snprintf(buf, sizeof buf, "%d hole%s or open border%s (%lld border vertices, the longest %.0f mm around)",
                holes, holes == 1 ? "" : "s", holes == 1 ? "" : "s", static_cast<long long>(border_vertices), longest);
  throw InvalidInput(std::string("the surface inside the curve has ") + buf +
                     ": the missing surface would be measured as empty space. Measure on a closed surface, "
                     "e.g. fitted.ply of `breastfit register` (report.json's volumes), or close the holes first");
}

}  // namespace

CurveVolume curve_volume(const TriangleMesh& mesh, const Points& closed_curve_mm, const CurveVolumeOptions& options,
                         VolumeCache* cache) {
  options.validate();
  VolumeCache own;  // without a cache: this call's own (the mesh's and the patch's topology, used twice each)
  VolumeCache& c = cache ? *cache : own;
  const CurveRegion region = find_region(mesh, closed_curve_mm, options.region, nullptr, &c);
  check_no_hole_inside(mesh, region, c);
  CurveVolume out;
  out.region = region.inside;
  out.mean_curve_distance_mm = region.mean_curve_distance_mm;

  // The patch under the curve: region ∪ loop, grown by the margin (generously) and two rings.
  TriangleMesh patch = patch_around(mesh, region, 1.5 * options.volume.margin_mm, &c);
  while (options.target_edge_mm > 0 && mean_edge_length(patch.V, patch.F) > options.target_edge_mm &&
         4 * static_cast<double>(patch.num_faces()) <= static_cast<double>(options.max_refined_faces)) {
    patch = mesh::subdivide(patch, /*loop=*/false);
    ++out.refinement_levels;
  }
  // On the refined patch the border of the measured region is the loop itself, moved onto the
  // curve: the membrane spans the curve, not the first vertices outside it (which would add a
  // band of up to an edge around it: +2 % at 2 mm edges on the bench's truth surfaces).
  std::vector<Vec3> border;
  const CurveRegion fine = find_region(patch, closed_curve_mm, options.region, &border, &c);
  std::vector<Index> strictly_inside;
  std::set_difference(fine.inside.begin(), fine.inside.end(), fine.loop.begin(), fine.loop.end(),
                      std::back_inserter(strictly_inside));
  if (strictly_inside.empty()) {  // a curve about one edge across: the vertices inside it
    out.volume_ml = region_volume(patch, fine.inside, options.volume, &c).volume_mm3 / 1000.0;
    out.measured_vertices = static_cast<Index>(fine.inside.size());
    return out;
  }
  for (size_t i = 0; i < fine.loop.size(); ++i) patch.V.row(fine.loop[i]) = border[i].transpose();
  out.volume_ml = region_volume(patch, strictly_inside, options.volume, &c).volume_mm3 / 1000.0;
  out.measured_vertices = static_cast<Index>(strictly_inside.size());
  return out;
}

double volume_inside_curve_ml(const TriangleMesh& mesh, const Points& closed_curve_mm, const CurveVolumeOptions& options) {
  return curve_volume(mesh, closed_curve_mm, options).volume_ml;
}

}  // namespace breastfit::transfer
