#pragma once
/// \file Legacy VTK reader (`.vtk`, as VTK, ParaView and 3D Slicer write: `# vtk DataFile
/// Version 2.0 … 5.1`, ASCII or BINARY — big-endian).
///
/// Datasets: POLYDATA (POLYGONS and TRIANGLE_STRIPS make triangles; VERTICES and LINES are read
/// and dropped) and UNSTRUCTURED_GRID (triangle, quad, pixel, polygon and triangle-strip cells
/// make triangles; vertices, lines and volume cells are dropped; a grid of volume cells only is
/// refused). Both cell layouts: the classic `count i0 i1 …` lists and VTK ≥ 5.1's OFFSETS /
/// CONNECTIVITY arrays. Convex polygons are fanned, concave ones ear-clipped in their plane,
/// strips alternate their winding (as PLY tristrips). POINT_DATA NORMALS, COLOR_SCALARS (3 or 4
/// values) and 2D TEXTURE_COORDINATES are kept; every other attribute, FIELD array and METADATA
/// block is skipped. A file whose title line says `SPACE=RAS` (3D Slicer's RAS frame) is
/// converted to LPS by negating x and y; `SPACE=LPS` or nothing keeps the coordinates as stored.
/// Counts are checked against the remaining data before anything is allocated.
#include <filesystem>
#include <string>
#include <string_view>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Reads a legacy VTK file.
/// \throws IoError(path, problem) when the file is missing, unreadable or malformed
TriangleMesh read_vtk(const std::filesystem::path& path);

/// Parses legacy VTK bytes held in memory (used by read_vtk and the fuzzers).
/// \param[in] bytes  whole file content
/// \param[in] name   name used in error messages (usually the path)
/// \throws IoError(name, problem) when the content is malformed
TriangleMesh read_vtk_from_memory(std::string_view bytes, const std::string& name);

}  // namespace breastfit::io
