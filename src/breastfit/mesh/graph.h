#pragma once
/// \file The edge graph of a triangle mesh (vertices joined by the triangles' edges, see
/// adjacency.h; an edge is as long as the straight segment between its vertices): distances grown
/// from a set of source vertices along the edges (Dijkstra), the shortest edge path between two
/// vertices (A*) and flood fills of connected pieces.
///
/// Distances along edges over-estimate the geodesic distance on the surface (a path along edges
/// zig-zags: up to 2/√3, about +15 %, across a regular triangle grid); they are meant for growing
/// regions by a margin and for joining nearby vertices, not for measuring.
///
/// Example:
/// \code
///   const auto nbr = breastfit::mesh::vertex_neighbours(mesh);
///   const std::vector<double> d = breastfit::mesh::edge_distances(mesh.V, nbr, region, 20.0);
///   // d[v] finite: v lies within 20 mm of the region along the edges
/// \endcode
#include <limits>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/adjacency.h"

namespace breastfit::mesh {

/// Shortest distance along the edges from the nearest source to every vertex, up to
/// `max_distance` (Dijkstra).
/// \param[in] V             #V by 3 vertex positions
/// \param[in] neighbours    vertex_neighbours() of the mesh (#V rows)
/// \param[in] sources       vertices at distance 0 (repeats allowed), each in [0, #V)
/// \param[in] max_distance  vertices farther than this (>= 0) stay unreached
/// \return #V distances: 0 at the sources, +inf where unreached (farther than max_distance, or
///         in another piece of the mesh)
/// \throws InvalidInput when a source is out of range or `neighbours` has not #V rows
std::vector<double> edge_distances(const Points& V, const AdjacencyLists& neighbours,
                                   const std::vector<Index>& sources,
                                   double max_distance = std::numeric_limits<double>::infinity());

/// Shortest edge paths between pairs of vertices (A* with the straight-line distance to the
/// target as heuristic, so the search stays near the segment between the two). Keeps its
/// per-vertex work arrays between queries: many short paths on a large mesh cost only what
/// each search touches.
class EdgePathFinder {
 public:
  /// \param V           #V by 3 vertex positions (kept by reference: must outlive the finder)
  /// \param neighbours  vertex_neighbours() of the mesh (kept by reference)
  EdgePathFinder(const Points& V, const AdjacencyLists& neighbours);

  /// The vertices of a shortest edge path from `from` to `to`, without `from`, ending with `to`;
  /// empty when `to` is not reached within `max_expansions` vertex expansions (or from == to).
  /// Ties between equally long paths are broken deterministically.
  std::vector<Index> path(Index from, Index to, int max_expansions);

 private:
  const Points& V_;
  const AdjacencyLists& nbr_;
  std::vector<double> g_;        // best known distance from `from` (+inf: untouched)
  std::vector<Index> parent_;    // predecessor on that path
  std::vector<Index> touched_;   // vertices whose g_ was set, reset after each query
};

/// Flood fill: gives `label` to `seed` and to every vertex reachable from it along edges
/// through vertices whose label is still negative and that are not blocked.
/// \param[in]     neighbours  vertex_neighbours() of the mesh
/// \param[in]     seed        start vertex (labelled even when blocked)
/// \param[in]     label       the label to write (>= 0)
/// \param[in,out] labels      #V labels; negative = not yet labelled
/// \param[in]     blocked     optional #V flags; a non-zero flag stops the fill at that vertex
void flood_fill(const AdjacencyLists& neighbours, Index seed, int label, std::vector<int>& labels,
                const std::vector<char>* blocked = nullptr);

}  // namespace breastfit::mesh
