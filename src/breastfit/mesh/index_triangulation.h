#pragma once
/// \file Triangles from index sequences: polygon fans and triangle strips, the two ways mesh
/// files (PLY faces and tristrips, STL facets, glTF primitive modes) list triangles by their
/// vertex indices. Triangles that repeat an index are skipped (strips use them as joins).
#include <cstddef>
#include <vector>

#include "breastfit/core/types.h"

namespace breastfit::mesh {

/// Appends the fan triangulation (c0, ci, ci+1) of `corners[0..count)` to `tris` (flat, 3
/// indices per triangle), skipping triangles that repeat a vertex index. Fewer than 3 corners
/// append nothing.
/// \return the number of triangles appended
int append_fan_triangles(const Index* corners, std::size_t count, std::vector<Index>& tris);

/// Appends the triangles of the strip `strip[0..count)` to `tris` with alternating winding, so
/// that all share the orientation of the first: (s0, s1, s2), (s2, s1, s3), (s2, s3, s4),
/// (s4, s3, s5), ... Triangles that repeat a vertex index are skipped. Fewer than 3 indices
/// append nothing.
/// \return the number of triangles appended
int append_strip_triangles(const Index* strip, std::size_t count, std::vector<Index>& tris);

}  // namespace breastfit::mesh
