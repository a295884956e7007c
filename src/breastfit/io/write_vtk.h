#pragma once
/// \file Legacy VTK writer (`.vtk`), readable by VTK, ParaView, PyVista and 3D Slicer.
///
/// `# vtk DataFile Version 3.0` (the classic cell layout every VTK version reads), title
/// `breastfit SPACE=LPS` (3D Slicer then loads the mesh in the frame of breastfit's markups),
/// BINARY (options.binary: big-endian, as the format requires) or ASCII; POINTS float (double
/// with options.double_precision); POLYGONS of 3 indices; POINT_DATA NORMALS (options.normals),
/// COLOR_SCALARS with 3 components (options.colors: unsigned char in binary files, [0,1] in
/// ascii ones) and TEXTURE_COORDINATES 2 (options.texcoords, per-vertex UV only). ASCII numbers
/// use the shortest text that reads back exactly.
#include <filesystem>
#include <string>

#include "breastfit/io/io.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Encodes a mesh as legacy VTK bytes.
/// \throws InvalidInput if the mesh is inconsistent (index out of range, attribute row counts)
std::string write_vtk_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options = {});

/// Writes a mesh as a legacy VTK file (overwritten).
/// \throws InvalidInput if the mesh is inconsistent
/// \throws IoError(path, problem) when the file cannot be written
void write_vtk(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options = {});

}  // namespace breastfit::io
