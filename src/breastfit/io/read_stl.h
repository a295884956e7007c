#pragma once
/// \file STL reader (ascii and binary).
///
/// Binary is recognised by its size (84 + 50·n bytes for the n triangles announced at byte 80),
/// even when the 80-byte header starts with "solid"; otherwise a file starting with "solid" is
/// read as ascii. Identical vertices (exact coordinate match) are merged into an indexed mesh;
/// triangles repeating a merged vertex are dropped. Facet normals are ignored (N stays empty).
#include <filesystem>
#include <string>
#include <string_view>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Reads an STL file.
/// \throws IoError(path, problem) when the file is missing, unreadable or malformed
TriangleMesh read_stl(const std::filesystem::path& path);

/// Parses STL bytes held in memory (used by read_stl and the fuzzers).
/// \param[in] bytes  whole file content
/// \param[in] name   name used in error messages (usually the path)
/// \throws IoError(name, problem) when the content is malformed
TriangleMesh read_stl_from_memory(std::string_view bytes, const std::string& name);

}  // namespace breastfit::io
