#include "breastfit/mesh/cleanup.h"

#include <algorithm>
#include <string>

#include "breastfit/core/errors.h"
#include "breastfit/mesh/components.h"
#include "breastfit/mesh/triangle_indices.h"

namespace breastfit::mesh {
namespace {

/// Keeps the triangles with keep[f] (and their FUV rows).
void keep_faces(TriangleMesh& mesh, const std::vector<bool>& keep) {
  const bool has_fuv = mesh.FUV.rows() == mesh.F.rows() && mesh.FUV.rows() > 0;
  Eigen::Index n = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (!keep[static_cast<size_t>(f)]) continue;
    mesh.F.row(n) = mesh.F.row(f);
    if (has_fuv) mesh.FUV.row(n) = mesh.FUV.row(f);
    ++n;
  }
  mesh.F.conservativeResize(n, 3);
  if (has_fuv) mesh.FUV.conservativeResize(n, 3);
}

}  // namespace

std::vector<bool> degenerate_faces(const Points& V, const Triangles& F,
                                   double relative_area_tolerance) {
  if (!(relative_area_tolerance >= 0.0))
    throw InvalidInput("relative_area_tolerance = " + std::to_string(relative_area_tolerance) +
                       " must be >= 0");
  check_triangle_indices(F, static_cast<Index>(V.rows()));
  std::vector<bool> bad(static_cast<size_t>(F.rows()), false);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Index i = F(f, 0), j = F(f, 1), k = F(f, 2);
    if (i == j || j == k || i == k) {
      bad[static_cast<size_t>(f)] = true;
      continue;
    }
    const Vec3 a = V.row(i).transpose(), b = V.row(j).transpose(), c = V.row(k).transpose();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double longest_sq =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    bad[static_cast<size_t>(f)] = !(area > relative_area_tolerance * longest_sq);
  }
  return bad;
}

Index count_degenerate_faces(const Points& V, const Triangles& F, double relative_area_tolerance) {
  const auto bad = degenerate_faces(V, F, relative_area_tolerance);
  return static_cast<Index>(std::count(bad.begin(), bad.end(), true));
}

std::vector<std::optional<Index>> remove_unreferenced_vertices(TriangleMesh& mesh) {
  const Index nv = mesh.num_vertices();
  std::vector<std::optional<Index>> map(static_cast<size_t>(nv));
  if (mesh.is_point_cloud()) {
    for (Index v = 0; v < nv; ++v) map[static_cast<size_t>(v)] = v;
    return map;
  }
  check_triangle_indices(mesh.F, nv);
  std::vector<bool> used(static_cast<size_t>(nv), false);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) used[static_cast<size_t>(mesh.F(f, c))] = true;
  const bool has_n = mesh.N.rows() == nv && nv > 0;
  const bool has_c = mesh.C.rows() == nv && nv > 0;
  Index n = 0;
  for (Index v = 0; v < nv; ++v) {
    if (!used[static_cast<size_t>(v)]) continue;
    map[static_cast<size_t>(v)] = n;
    mesh.V.row(n) = mesh.V.row(v);
    if (has_n) mesh.N.row(n) = mesh.N.row(v);
    if (has_c) mesh.C.row(n) = mesh.C.row(v);
    ++n;
  }
  mesh.V.conservativeResize(n, 3);
  if (has_n) mesh.N.conservativeResize(n, 3);
  if (has_c) mesh.C.conservativeResize(n, 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) mesh.F(f, c) = *map[static_cast<size_t>(mesh.F(f, c))];
  return map;
}

Index remove_degenerate_faces(TriangleMesh& mesh, double relative_area_tolerance) {
  std::vector<bool> keep = degenerate_faces(mesh.V, mesh.F, relative_area_tolerance);
  const Index removed = static_cast<Index>(std::count(keep.begin(), keep.end(), true));
  if (removed == 0) return 0;
  keep.flip();
  keep_faces(mesh, keep);
  return removed;
}

Index remove_small_components(TriangleMesh& mesh, Index min_faces) {
  if (min_faces < 1)
    throw InvalidInput("min_faces = " + std::to_string(min_faces) + " must be >= 1");
  const Components comps = connected_components(mesh);
  Index removed = 0;
  for (Index c = 0; c < comps.count(); ++c)
    if (comps.face_count[static_cast<size_t>(c)] < min_faces) ++removed;
  if (removed == 0) return 0;
  std::vector<bool> keep(static_cast<size_t>(mesh.F.rows()));
  for (size_t f = 0; f < keep.size(); ++f)
    keep[f] = comps.face_count[static_cast<size_t>(comps.face_label[f])] >= min_faces;
  keep_faces(mesh, keep);
  return removed;
}

void CleanupOptions::validate() const {
  if (!(relative_area_tolerance >= 0.0))
    throw InvalidInput("CleanupOptions.relative_area_tolerance = " +
                       std::to_string(relative_area_tolerance) + " must be >= 0");
  if (min_component_faces < 1)
    throw InvalidInput("CleanupOptions.min_component_faces = " +
                       std::to_string(min_component_faces) + " must be >= 1");
}

CleanupSummary cleanup(TriangleMesh& mesh, const CleanupOptions& options) {
  options.validate();
  check_triangle_indices(mesh.F, mesh.num_vertices());
  CleanupSummary s;
  if (options.remove_degenerate)
    s.removed_degenerate_faces = remove_degenerate_faces(mesh, options.relative_area_tolerance);
  if (options.remove_small_components) {
    const Index before = mesh.num_faces();
    s.removed_components = remove_small_components(mesh, options.min_component_faces);
    s.removed_component_faces = before - mesh.num_faces();
  }
  if (options.remove_unreferenced) {
    const Index before = mesh.num_vertices();
    s.old_to_new_vertex = remove_unreferenced_vertices(mesh);
    s.removed_vertices = before - mesh.num_vertices();
  } else {
    s.old_to_new_vertex.resize(static_cast<size_t>(mesh.num_vertices()));
    for (Index v = 0; v < mesh.num_vertices(); ++v) s.old_to_new_vertex[static_cast<size_t>(v)] = v;
  }
  return s;
}

}  // namespace breastfit::mesh
