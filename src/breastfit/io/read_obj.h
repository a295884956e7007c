#pragma once
/// \file Wavefront OBJ reader (our own parser; see docs/IO.md for why not tinyobjloader).
///
/// Reads `v x y z [w]` (or `v x y z r g b`: colours kept when every vertex has them; values in
/// [0,1] are scaled to 0..255), `vt u [v [w]]` (kept as UV/FUV when every face has them),
/// `vn x y z` (mapped to per-vertex normals through the faces), `f` in all index forms (v, v/vt,
/// v//vn, v/vt/vn) with negative (relative) indices; convex polygons are fan-triangulated,
/// concave ones ear-clipped in their best-fit plane (detail/polygon_triangulation.h); triangles
/// repeating a vertex are dropped. Lines ending in `\` continue on the next line. g, o, s,
/// usemtl, mtllib, l, p and unknown statements are ignored.
#include <filesystem>
#include <string>
#include <string_view>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Reads an OBJ file.
/// \throws IoError(path, problem) when the file is missing, unreadable or malformed
TriangleMesh read_obj(const std::filesystem::path& path);

/// Parses OBJ text held in memory (used by read_obj and the fuzzers).
/// \param[in] bytes  whole file content
/// \param[in] name   name used in error messages (usually the path)
/// \throws IoError(name, problem) when the content is malformed
TriangleMesh read_obj_from_memory(std::string_view bytes, const std::string& name);

}  // namespace breastfit::io
