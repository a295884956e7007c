#pragma once
/// \file The range check of a triangle list's vertex indices, shared by every mesh kernel that
/// indexes vertices through F.
#include "breastfit/core/types.h"

namespace breastfit::mesh {

/// Checks that every index of F lies in [0, num_vertices).
/// \throws InvalidInput naming the first offending triangle ("triangle f has vertex index i
///         outside [0, n)")
void check_triangle_indices(const Triangles& F, Index num_vertices);

}  // namespace breastfit::mesh
