#pragma once
/// \file PLY writer.
///
/// PLY: binary_little_endian (options.binary) or ascii; x,y,z as float (or double with
/// options.double_precision); optional nx,ny,nz, uchar red,green,blue, per-vertex u,v; faces as
/// `list uchar int vertex_indices`. ASCII values use the shortest text that reads back exactly.
#include <filesystem>
#include <string>

#include "breastfit/io/io.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Encodes a mesh as PLY bytes.
/// \throws InvalidInput if the mesh is inconsistent (index out of range, attribute row counts)
std::string write_ply_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options = {});

/// Writes a mesh as a PLY file (overwritten).
/// \throws InvalidInput if the mesh is inconsistent
/// \throws IoError(path, problem) when the file cannot be written
void write_ply(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options = {});

}  // namespace breastfit::io
