#pragma once
/// \file Marching tetrahedra: the zero set of a scalar field sampled on a regular grid, as a
/// manifold, consistently oriented triangle mesh (normals towards the positive side).
#include <functional>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::templ {

/// Samples `field` on the grid lo + (i, j, k) * step covering [lo, hi] and extracts the zero
/// set by splitting every cell into 6 tetrahedra (Kuhn split, no ambiguous cases). The field is
/// negative inside; triangles face the positive side. Grid nodes with a value of exactly 0 are
/// treated as slightly positive.
/// \throws InvalidInput when step <= 0 or the box is empty.
TriangleMesh marching_tetrahedra(const std::function<double(const Vec3&)>& field, const Vec3& lo,
                                 const Vec3& hi, double step);

}  // namespace breastfit::templ
