#include "breastfit/fit/skin_around.h"

#include "breastfit/mesh/components.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::fit {

std::vector<char> skin_vertices(const TriangleMesh& scan) {
  std::vector<char> out(static_cast<size_t>(scan.num_vertices()), 1);
  if (scan.is_point_cloud()) return out;
  // A vertex no triangle uses counts 0 triangles: below the (positive) minimum, not skin.
  const std::vector<Index> piece_triangles = mesh::component_size_per_vertex(scan);
  const double min_triangles = kMinSkinPieceFraction * static_cast<double>(scan.num_faces());
  for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<double>(piece_triangles[i]) >= min_triangles;
  return out;
}

namespace {

// The rows `kept` of the scan's vertices and normals.
SkinPatch patch_of(const Points& V, const Points& scan_normals, const std::vector<Index>& kept) {
  SkinPatch out;
  out.V.resize(static_cast<Index>(kept.size()), 3);
  out.N.resize(static_cast<Index>(kept.size()), 3);
  for (Index k = 0; k < static_cast<Index>(kept.size()); ++k) {
    out.V.row(k) = V.row(kept[k]);
    out.N.row(k) = scan_normals.row(kept[k]);
  }
  return out;
}

// Whether scan vertex i is in the patch: on the skin and within the radius (both overloads' test).
bool in_patch(const Points& V, const std::vector<char>& skin, Index i, const Vec3& centre, double radius_mm) {
  return skin[static_cast<size_t>(i)] && (V.row(i).transpose() - centre).norm() < radius_mm;
}

// The index's query radius around a patch of `radius_mm`: relatively this much wider, so that
// its own rounding of the distances cannot leave out a vertex the exact test keeps.
constexpr double kQueryWidening = 1e-6;

}  // namespace

SkinPatch skin_around(const TriangleMesh& scan, const Points& scan_normals, const std::vector<char>& skin,
                      const Vec3& centre, double radius_mm) {
  std::vector<Index> kept;
  for (Index i = 0; i < scan.num_vertices(); ++i)
    if (in_patch(scan.V, skin, i, centre, radius_mm)) kept.push_back(i);
  return patch_of(scan.V, scan_normals, kept);
}

SkinPatch skin_around(const spatial::ClosestPointIndex& index, const Points& scan_normals,
                      const std::vector<char>& skin, const Vec3& centre, double radius_mm) {
  const Points& V = index.mesh().V;
  std::vector<Index> near;  // ascending, each once
  index.vertices_within(centre, radius_mm * (1 + kQueryWidening), near);
  std::vector<Index> kept;
  for (const Index i : near)
    if (in_patch(V, skin, i, centre, radius_mm)) kept.push_back(i);
  return patch_of(V, scan_normals, kept);
}

}  // namespace breastfit::fit
