#pragma once
/// \file PLY reader (ascii, binary_little_endian, binary_big_endian).
///
/// Vertex element: x,y,z of any scalar type (required); nx,ny,nz (kept as TriangleMesh::N);
/// red,green,blue or diffuse_red,... (uchar kept, float in [0,1] scaled to 0..255, kept as C);
/// u,v / s,t / texture_u,texture_v (kept as per-vertex UV with FUV = F). Face element: list
/// property `vertex_indices` or `vertex_index` with any integer count and index types; convex
/// polygons are fan-triangulated, concave ones ear-clipped in their plane (as the OBJ reader
/// does), triangles repeating a vertex are dropped. Tristrips element (as some
/// scanners write): the same list property holds triangle strips separated by the restart index
/// -1, triangulated with alternating winding ((v0,v1,v2), (v2,v1,v3), (v2,v3,v4), ...), dropping
/// those repeating a vertex; face and strip triangles follow the header's element order. Other elements and properties (including
/// list properties) are skipped. A file with vertices only is a point cloud.
/// Counts in the header are checked against the data size before anything is allocated.
#include <filesystem>
#include <string>
#include <string_view>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Reads a PLY file.
/// \throws IoError(path, problem) when the file is missing, unreadable or malformed
TriangleMesh read_ply(const std::filesystem::path& path);

/// Parses PLY bytes held in memory (used by read_ply and the fuzzers).
/// \param[in] bytes  whole file content
/// \param[in] name   name used in error messages (usually the path)
/// \throws IoError(name, problem) when the content is malformed
TriangleMesh read_ply_from_memory(std::string_view bytes, const std::string& name);

}  // namespace breastfit::io
