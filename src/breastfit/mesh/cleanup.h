#pragma once
/// \file Mesh cleanup: unreferenced vertices, degenerate triangles, small components.
///
/// Per-vertex attributes (N, C) follow their vertices; per-face texture indices (FUV) follow their
/// triangles (UV itself is left as is). Units-agnostic: the degenerate-triangle test is relative
/// to each triangle's own size.
#include <optional>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::mesh {

/// Default relative-area tolerance of is_degenerate_face: area <= 1e-12 * (longest edge)^2, i.e.
/// the triangle is collinear to about 1e-12 of its size.
inline constexpr double kDegenerateRelativeArea = 1e-12;

/// Per-triangle flag: true when the triangle repeats a vertex index or its area is at most
/// `relative_area_tolerance` times its longest edge squared (zero area, collinear corners).
/// \param[in] V, F  mesh (indices in range)
/// \return #F flags
/// \throws InvalidInput for an index out of range or a negative tolerance
std::vector<bool> degenerate_faces(const Points& V, const Triangles& F,
                                   double relative_area_tolerance = kDegenerateRelativeArea);

/// Number of true entries of degenerate_faces.
Index count_degenerate_faces(const Points& V, const Triangles& F,
                             double relative_area_tolerance = kDegenerateRelativeArea);

/// Removes vertices that no triangle uses, compacting V (and N, C when present) and re-indexing F.
/// A point cloud (no triangles) is left unchanged: its vertices are the data.
/// \param[in,out] mesh  mesh to compact
/// \return #V_old map old index -> new index (nullopt for a removed vertex)
std::vector<std::optional<Index>> remove_unreferenced_vertices(TriangleMesh& mesh);

/// Removes the triangles flagged by degenerate_faces (vertices are kept).
/// \return number of triangles removed
Index remove_degenerate_faces(TriangleMesh& mesh,
                              double relative_area_tolerance = kDegenerateRelativeArea);

/// Removes the triangles of every connected component (see components.h) with fewer than
/// `min_faces` triangles (vertices are kept; call remove_unreferenced_vertices afterwards).
/// \return number of components removed
Index remove_small_components(TriangleMesh& mesh, Index min_faces);

/// What cleanup() does, in this order: degenerate triangles, small components, unreferenced
/// vertices.
struct CleanupOptions {
  bool remove_degenerate = true;                         ///< drop zero-area / repeated-index triangles
  double relative_area_tolerance = kDegenerateRelativeArea;  ///< see degenerate_faces; >= 0
  bool remove_small_components = false;                  ///< drop small floating pieces
  Index min_component_faces = 100;                       ///< components with fewer triangles go; >= 1
  bool remove_unreferenced = true;                       ///< compact vertices no triangle uses

  /// \throws InvalidInput naming the field, value and rule
  void validate() const;
};

/// What cleanup() removed.
struct CleanupSummary {
  Index removed_degenerate_faces = 0;
  Index removed_components = 0;
  Index removed_component_faces = 0;
  Index removed_vertices = 0;
  std::vector<std::optional<Index>> old_to_new_vertex;  ///< #V_old; identity when nothing removed
};

/// Cleans a mesh in place (see CleanupOptions).
/// \throws InvalidInput for invalid options or out-of-range indices
CleanupSummary cleanup(TriangleMesh& mesh, const CleanupOptions& options = {});

}  // namespace breastfit::mesh
