#pragma once
/// \file OBJ writer.
///
/// OBJ: `v` (plus r g b in [0,1] with options.colors), `vt` (options.texcoords), `vn`
/// (options.normals, one per vertex), `f` in the matching index form. Numbers use the shortest
/// text that reads back exactly. options.binary and options.double_precision are ignored.
#include <filesystem>
#include <string>

#include "breastfit/io/io.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Encodes a mesh as OBJ bytes.
/// \throws InvalidInput if the mesh is inconsistent (index out of range, attribute row counts)
std::string write_obj_to_memory(const TriangleMesh& mesh, const MeshWriteOptions& options = {});

/// Writes a mesh as an OBJ file (overwritten).
/// \throws InvalidInput if the mesh is inconsistent
/// \throws IoError(path, problem) when the file cannot be written
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               const MeshWriteOptions& options = {});

}  // namespace breastfit::io
