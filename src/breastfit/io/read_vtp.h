#pragma once
/// \file VTK XML PolyData reader (`.vtp`, as VTK, ParaView, PyVista and 3D Slicer write).
///
/// Every data layout VTK writes: `format="ascii"`, inline `binary` (base64) and `appended`
/// (`encoding="raw"` or `"base64"`), uncompressed or zlib-compressed (`vtkZLibDataCompressor`;
/// other compressors are refused), `header_type` UInt32 or UInt64, either byte order. Every
/// `<Piece>` is read (their points and cells concatenated). `<Polys>` and `<Strips>` make
/// triangles (convex polygons fanned, concave ones ear-clipped in their plane, strips with
/// alternating winding); `<Verts>` and `<Lines>` are ignored. The point data's active
/// `Normals`, `TCoords` (2 components) and `Scalars` when they are 3- or 4-component UInt8
/// colours are kept. A field-data string array `SPACE` saying RAS (3D Slicer's RAS frame) makes
/// the reader convert to LPS by negating x and y. Sizes are checked against the file (and the
/// compressed blocks' declared sizes against the array's) before anything is inflated.
#include <filesystem>
#include <string>
#include <string_view>

#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::io {

/// Reads a VTK XML PolyData file.
/// \throws IoError(path, problem) when the file is missing, unreadable or malformed
TriangleMesh read_vtp(const std::filesystem::path& path);

/// Parses .vtp bytes held in memory (used by read_vtp and the fuzzers).
/// \param[in] bytes  whole file content
/// \param[in] name   name used in error messages (usually the path)
/// \throws IoError(name, problem) when the content is malformed
TriangleMesh read_vtp_from_memory(std::string_view bytes, const std::string& name);

}  // namespace breastfit::io
