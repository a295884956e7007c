#pragma once
/// \file Mesh file front door: read or write a triangle mesh choosing the format by extension.
///
/// Supported: `.ply` (ascii, binary little/big endian), `.obj`, `.stl` (ascii and binary),
/// `.vtk` (legacy VTK, ascii and binary) and, for reading only, `.vtp` (VTK XML PolyData);
/// extensions are matched case-insensitively. Coordinates are returned exactly as stored in the
/// file: no unit conversion happens here (see the mesh layer for units). Every problem with a
/// file — missing, a directory, unknown extension, truncated, lying header, bad index,
/// non-finite coordinate, random bytes — is reported as a breastfit::IoError whose one-line
/// message names the file and the problem. See docs/IO.md for the exact policy.
///
/// Example:
/// \code
///   breastfit::TriangleMesh scan = breastfit::io::read_mesh("scan.ply");
///   breastfit::io::write_mesh("scan.obj", scan, {.binary = false, .normals = true});
/// \endcode
#include <filesystem>
#include <string_view>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// The mesh file extensions read_mesh and write_mesh accept, as error messages list them.
inline constexpr std::string_view kMeshExtensions = ".ply, .obj, .stl, .vtk, .vtp";
/// The mesh file extensions write_mesh accepts.
inline constexpr std::string_view kMeshWriteExtensions = ".ply, .obj, .stl, .vtk";

/// How write_mesh and the per-format writers encode a mesh.
struct MeshWriteOptions {
  bool binary =
      true;  ///< PLY: binary_little_endian (true) or ascii; STL: binary or ascii; OBJ: ignored
  bool normals = false;   ///< write per-vertex normals when the mesh has them
  bool colors = false;    ///< write per-vertex RGB colours when the mesh has them (PLY, OBJ)
  bool texcoords = true;  ///< write texture coordinates when the mesh has them (OBJ vt; PLY u,v
                          ///< only when they are per vertex, i.e. FUV == F and #UV == #V)
  bool double_precision = false;  ///< PLY: store x,y,z (and normals) as double instead of float
                                  ///< (float is the scanner convention and halves the file size)
};

/// Whether the path ends in one of kMeshExtensions (case-insensitive).
bool has_mesh_extension(const std::filesystem::path& path);

/// Reads a mesh (or point cloud, F empty) choosing the reader by extension (.ply .obj .stl .vtk
/// .vtp).
/// \param[in] path  file to read
/// \return the mesh; V in file units, F fan-triangulated, optional N, C, UV/FUV
/// \throws IoError(path, problem) for a missing file, a directory, an unknown extension or any
///         malformed content
TriangleMesh read_mesh(const std::filesystem::path& path);

/// Writes a mesh choosing the writer by extension (.ply .obj .stl .vtk).
/// \param[in] path     destination (overwritten)
/// \param[in] mesh     mesh to write; indices must be in range
/// \param[in] options  encoding options (defaults: binary, no normals, no colours, texcoords)
/// \throws InvalidInput if the mesh is inconsistent (index out of range, attribute row counts)
/// \throws IoError(path, problem) for an unknown extension or when the file cannot be written
void write_mesh(const std::filesystem::path& path, const TriangleMesh& mesh,
                const MeshWriteOptions& options = {});

}  // namespace breastfit::io
