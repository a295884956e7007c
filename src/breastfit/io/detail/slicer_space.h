#pragma once
/// \file The coordinate system 3D Slicer declares in the mesh files it writes (private to the io
/// layer): since Slicer 4.11 models are saved in LPS with `SPACE=LPS` in the file header (legacy
/// .vtk title line) or in a field-data string array named `SPACE` (.vtp); `SPACE=RAS` marks a
/// file in Slicer's internal RAS frame. A file saying nothing is taken as stored (Slicer itself
/// then assumes LPS).
#include <string_view>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io::detail {

/// What a file declares about its frame.
enum class SlicerSpace { Unstated, Lps, Ras };

/// The space a header text declares with `SPACE=RAS` / `SPACE=LPS` (Unstated when neither).
SlicerSpace slicer_space_in_header(std::string_view header);

/// The space a `SPACE` field-data value names (`RAS` or `LPS` in it; Unstated otherwise).
SlicerSpace slicer_space_in_value(std::string_view value);

/// Converts a mesh read in RAS to LPS, breastfit's frame for Slicer data (as the markups reader
/// does): x and y (and the normals' x and y) are negated — a rotation by 180° about z, so the
/// triangles keep their winding.
void ras_to_lps(TriangleMesh& mesh);

}  // namespace breastfit::io::detail
