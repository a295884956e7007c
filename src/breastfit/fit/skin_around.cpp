#include "breastfit/fit/skin_around.h"

#include "breastfit/mesh/components.h"

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

SkinPatch skin_around(const TriangleMesh& scan, const Points& scan_normals, const std::vector<char>& skin,
                      const Vec3& centre, double radius_mm) {
  std::vector<Index> kept;
  for (Index i = 0; i < scan.num_vertices(); ++i)
    if (skin[static_cast<size_t>(i)] && (scan.V.row(i).transpose() - centre).norm() < radius_mm) kept.push_back(i);
  SkinPatch out;
  out.V.resize(static_cast<Index>(kept.size()), 3);
  out.N.resize(static_cast<Index>(kept.size()), 3);
  for (Index k = 0; k < static_cast<Index>(kept.size()); ++k) {
    out.V.row(k) = scan.V.row(kept[k]);
    out.N.row(k) = scan_normals.row(kept[k]);
  }
  return out;
}

}  // namespace breastfit::fit
