#pragma once
/// \file Helpers turning the flat arrays the readers fill into TriangleMesh matrices, and the
/// consistency check the writers run (private to the io layer).
#include <cstdint>
#include <vector>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io::detail {

/// Appends the fan triangulation (c0, ci, ci+1) of the polygon `corners[0..count)` to `tris`
/// (flat, 3 indices per triangle), skipping triangles that repeat a vertex index.
/// \pre count >= 3
/// \return the number of triangles appended
int append_fan(const Index* corners, std::size_t count, std::vector<Index>& tris);

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
