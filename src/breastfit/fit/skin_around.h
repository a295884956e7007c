#pragma once
/// \file The scan's skin around a point: the scan's vertices near it that lie on a piece of the scan
/// big enough to be the body, not on a floating fragment in front of it.
///
/// The nipple's checks search the scan around the predicted nipple for the breast's tip (the vertex
/// farthest along the mean outward normal, landmark_check.h breast_tip_on_scan) and apex
/// (nipple_apex.h). Over every scan vertex that close, a floating fragment (clothing, hair, a
/// reconstruction artefact in front of the breast) projects further than the skin and becomes the
/// "tip": on two of 24 template-made torsos (`breastfit synth`, 3 floating fragments each) a
/// fragment of ~50 vertices was taken 38 and 42 mm from the nipple as given — false flags
/// (docs/REGISTRATION.md, session 20). The skin is the vertices of the scan's connected pieces
/// (mesh/components.h: triangles sharing a vertex) holding at least kMinSkinPieceFraction of its
/// triangles. The pieces are the whole scan's, not those of the triangles near the point: a hole
/// near the nipple can cut the skin there into pieces that are one around the hole.
/// A scan without triangles (a point cloud) is skin everywhere.
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::spatial {
class ClosestPointIndex;
}

namespace breastfit::fit {

/// A piece of the scan with fewer triangles than this share of the scan's is a fragment, not skin.
inline constexpr double kMinSkinPieceFraction = 0.01;

/// Per scan vertex: 1 when it lies on the skin (a piece with at least kMinSkinPieceFraction of the
/// scan's triangles; every vertex of a point cloud), else 0 (a fragment's, or used by no triangle).
std::vector<char> skin_vertices(const TriangleMesh& scan);

/// Scan vertices and their normals (rows alike).
struct SkinPatch {
  Points V;
  Points N;
};

/// The skin's vertices (`skin`, from skin_vertices) within `radius_mm` of `centre`, in ascending scan
/// order, with their rows of `scan_normals`.
SkinPatch skin_around(const TriangleMesh& scan, const Points& scan_normals, const std::vector<char>& skin,
                      const Vec3& centre, double radius_mm);
/// The same patch, bit for bit, on the scan `index` was built over (`skin` from skin_vertices of
/// it), from the index's vertices within a hair more than the radius (ClosestPointIndex::vertices_within:
/// the tree's boxes prune) instead of a pass over every scan vertex; the same test, the same order.
/// A skin vertex lies on a triangle, so none is missed. \throws InvalidInput when `radius_mm` is
/// negative or not finite.
SkinPatch skin_around(const spatial::ClosestPointIndex& index, const Points& scan_normals,
                      const std::vector<char>& skin, const Vec3& centre, double radius_mm);

}  // namespace breastfit::fit
