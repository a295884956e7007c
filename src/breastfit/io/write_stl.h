#pragma once
/// \file STL writer.
///
/// STL: binary (options.binary) or ascii, float coordinates, facet normals computed from the
/// triangles. Normals, colours and texture coordinates are not stored (the format has none).
#include <filesystem>
#include <string>

#include "breastfit/io/io.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Encodes a mesh as STL bytes.
/// \throws InvalidInput if the mesh is inconsistent (index out of range, attribute row counts)
std::string write_stl_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options = {});

/// Writes a mesh as a STL file (overwritten).
/// \throws InvalidInput if the mesh is inconsistent
/// \throws IoError(path, problem) when the file cannot be written
void write_stl(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options = {});

}  // namespace breastfit::io
