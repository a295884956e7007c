#pragma once
/// \file A point on a triangle mesh stored as (triangle, barycentric coordinates), so that it
/// moves with the mesh (landmarks and drawings of the rigged template).
#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit {

struct SurfacePoint {
  Index face = 0;                        ///< triangle index
  Vec3 bary = Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3);  ///< barycentric weights of the triangle's 3 corners, sum 1

  /// Position on a mesh with the same triangles (any vertex positions).
  Vec3 position(const Points& V, const Triangles& F) const {
    return bary[0] * V.row(F(face, 0)).transpose() + bary[1] * V.row(F(face, 1)).transpose() +
           bary[2] * V.row(F(face, 2)).transpose();
  }
};

}  // namespace breastfit
