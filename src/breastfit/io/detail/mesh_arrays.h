#pragma once
/// \file Helpers turning the flat arrays the readers fill into TriangleMesh matrices, and the
/// consistency check the writers run (private to the io layer).
#include <cstdint>
#include <vector>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io::detail {

/// Copies a flat row-major array with `cols` columns into a matrix with that many columns.
Points to_points(const std::vector<double>& flat);
Triangles to_triangles(const std::vector<Index>& flat);
TexCoords to_texcoords(const std::vector<double>& flat);
Colors to_colors(const std::vector<std::uint8_t>& flat);

/// Checks what the writers rely on: F indices in [0, #V), N and C empty or #V rows, FUV empty
/// or #F rows with indices in [0, #UV).
/// \throws InvalidInput naming the first inconsistency
void check_mesh_for_writing(const TriangleMesh& mesh);

}  // namespace breastfit::io::detail
