#pragma once
/// \file Open borders of a triangle mesh: boundary edges, boundary vertices, boundary loops, and
/// non-manifold edges.
///
/// An (undirected) edge is a *boundary* edge when exactly one triangle uses it and *non-manifold*
/// when three or more do. Triangles that repeat a vertex index (no area, see cleanup.h) are
/// ignored here. Scans have many boundary loops (holes, the cropped outline); the fit
/// rejects correspondences that land on them. Units-agnostic.
#include <array>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::mesh {

/// Edges used by exactly one triangle, each oriented as in that triangle (a -> b), sorted by
/// (min(a,b), max(a,b)).
/// \param[in] F  #F by 3 vertex indices
std::vector<std::array<Index, 2>> boundary_edges(const Triangles& F);

/// Per-vertex flag: true when the vertex is an endpoint of a boundary edge.
/// \param[in] F             #F by 3 vertex indices, each in [0, num_vertices)
/// \param[in] num_vertices  #V
/// \return #V flags (all false for a point cloud)
/// \throws InvalidInput if an index is out of range
std::vector<bool> boundary_vertices(const Triangles& F, Index num_vertices);
std::vector<bool> boundary_vertices(const TriangleMesh& mesh);

/// The boundary edges chained into loops. Each loop is an ordered list of vertex indices, the
/// closing edge (last -> first) implied, walking the edges in their triangles' direction (for a
/// consistently oriented mesh the border is traversed with the surface on the left, seen from the
/// normal side). Where a vertex has several boundary edges (pinched borders) loops are split
/// deterministically; a chain that cannot be closed (non-manifold or inconsistently oriented
/// input) is returned as it was walked.
/// \param[in] F  #F by 3 vertex indices
/// \return loops in order of their smallest boundary edge; empty for a closed mesh
std::vector<std::vector<Index>> boundary_loops(const Triangles& F);
std::vector<std::vector<Index>> boundary_loops(const TriangleMesh& mesh);

/// Number of undirected edges used by three or more triangles.
Index count_non_manifold_edges(const Triangles& F);

/// Length of a closed polyline through V[loop[0]], ..., V[loop[n-1]], back to V[loop[0]].
/// \return mesh units; 0 for fewer than 2 vertices
double loop_length(const Points& V, const std::vector<Index>& loop);

}  // namespace breastfit::mesh
