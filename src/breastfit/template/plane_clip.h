#pragma once
/// \file Clipping a triangle mesh by region-limited planes (the cuts of the template body).
#include <cstdint>
#include <vector>

#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/template/body_field.h"

namespace breastfit::templ {

/// A clipped mesh and, per vertex, a bit mask of the cuts it lies on (bit c = cuts[c]).
struct ClippedMesh {
  TriangleMesh mesh;
  std::vector<std::uint32_t> on_cut;  ///< #V bit masks; 0 for vertices off every cut
};

/// Removes the parts of `mesh` on the positive side of each cut (within its region), splitting
/// the triangles that cross a cut so that the new boundary vertices lie exactly on the plane.
/// Then drops unreferenced vertices and keeps only the largest connected component.
/// \throws InvalidInput when more than 32 cuts are given or nothing is left.
ClippedMesh clip_by_planes(const TriangleMesh& mesh, const std::vector<CutPlane>& cuts);

}  // namespace breastfit::templ
