#pragma once
/// \file Connected components of a triangle mesh (triangles connected through shared vertices).
#include <optional>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::mesh {

/// Component labels and sizes. Components are numbered 0..count()-1 by decreasing number of
/// triangles (ties: by smallest triangle index), so component 0 is the largest piece.
struct Components {
  std::vector<Index> face_label;                  ///< #F component of each triangle
  std::vector<std::optional<Index>> vertex_label; ///< #V component of each vertex; nullopt for a
                                                  ///< vertex no triangle uses (point-cloud vertex)
  std::vector<Index> face_count;                  ///< triangles per component
  std::vector<Index> vertex_count;                ///< (referenced) vertices per component

  Index count() const { return static_cast<Index>(face_count.size()); }
};

/// Labels the connected components: two triangles are connected when they share a vertex
/// (so pieces touching at a single vertex are one component). Unreferenced vertices belong to
/// no component.
/// \param[in] F             #F by 3 vertex indices, each in [0, num_vertices)
/// \param[in] num_vertices  #V
/// \throws InvalidInput if an index is out of range
Components connected_components(const Triangles& F, Index num_vertices);
Components connected_components(const TriangleMesh& mesh);

/// Per vertex, how many triangles its connected component has (connected_components' face_count
/// of its label), 0 for a vertex no triangle uses: the components' sizes without labelling or
/// ordering them (fit/skin_around.cpp asks only how big each vertex's piece is, once per fit: the
/// labels cost more than the union-find).
/// \throws InvalidInput if an index is out of range
std::vector<Index> component_size_per_vertex(const TriangleMesh& mesh);

}  // namespace breastfit::mesh
