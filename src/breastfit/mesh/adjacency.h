#pragma once
/// \file Vertex adjacency of a triangle mesh in compressed sparse row (CSR) layout: the
/// neighbours of every vertex along the triangles' edges, the triangles around every vertex, and
/// the mesh's unique undirected edges.
///
/// Rules shared by all three: an edge joins two different vertices (a triangle repeating an
/// index contributes only its proper edges, and no vertex is its own neighbour); a vertex no
/// triangle uses has no neighbours and no triangles.
///
/// Example:
/// \code
///   const breastfit::mesh::AdjacencyLists nbr = breastfit::mesh::vertex_neighbours(mesh);
///   for (breastfit::Index w : nbr[v]) visit(w);   // sorted, unique
/// \endcode
#include <array>
#include <span>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::mesh {

/// Lists of indices, one per row, stored back to back: row r is
/// items[offsets[r] .. offsets[r + 1]), ascending within the row.
struct AdjacencyLists {
  std::vector<Index> offsets{0};  ///< #rows + 1, offsets[0] = 0, non-decreasing
  std::vector<Index> items;       ///< all rows' items, row after row

  /// Number of rows (vertices).
  Index num_rows() const { return static_cast<Index>(offsets.size()) - 1; }
  /// The items of row r (0 <= r < num_rows()).
  std::span<const Index> operator[](Index r) const {
    const auto b = static_cast<size_t>(offsets[static_cast<size_t>(r)]);
    const auto e = static_cast<size_t>(offsets[static_cast<size_t>(r) + 1]);
    return {items.data() + b, e - b};
  }
  /// Number of items of row r.
  Index size(Index r) const {
    return offsets[static_cast<size_t>(r) + 1] - offsets[static_cast<size_t>(r)];
  }
  /// True when row r holds x (binary search: rows are sorted).
  bool contains(Index r, Index x) const;
};

/// Neighbours of every vertex along the triangles' edges: sorted, unique, never the vertex
/// itself. Linear time (one counting pass, one fill, a sort per vertex).
/// \param[in] F             #F by 3 vertex indices
/// \param[in] num_vertices  #V (rows of the result)
/// \throws InvalidInput if an index of F is outside [0, num_vertices)
AdjacencyLists vertex_neighbours(const Triangles& F, Index num_vertices);
AdjacencyLists vertex_neighbours(const TriangleMesh& mesh);

/// Triangles around every vertex: the faces using it, ascending, each listed once (also when
/// the face repeats the vertex).
/// \throws InvalidInput if an index of F is outside [0, num_vertices)
AdjacencyLists vertex_faces(const Triangles& F, Index num_vertices);
AdjacencyLists vertex_faces(const TriangleMesh& mesh);

/// Unique undirected edges {a, b}, a < b, sorted by a then b (the pairs of vertex_neighbours
/// with a < b).
/// \throws InvalidInput if an index of F is outside [0, num_vertices)
std::vector<std::array<Index, 2>> unique_edges(const Triangles& F, Index num_vertices);

}  // namespace breastfit::mesh
