#pragma once
/// \file Summary statistics of a mesh or point cloud (what `breastfit inspect` reports).
#include <optional>
#include <string>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/mesh/units.h"

namespace breastfit::mesh {

/// Lengths of the unique (undirected) edges, in mesh units.
struct EdgeLengthStats {
  Index count = 0;     ///< number of unique edges
  double min = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double max = 0.0;
};

/// One open border of the mesh (see boundary.h).
struct BoundaryLoopStats {
  Index num_vertices = 0;  ///< vertices on the loop
  double length = 0.0;     ///< closed polyline length, mesh units
};

/// Everything inspect prints about a mesh, in the mesh's own units unless the name says mm.
struct MeshStats {
  Index num_vertices = 0;
  Index num_faces = 0;
  bool is_point_cloud = false;
  bool has_normals = false;
  bool has_colors = false;
  bool has_texcoords = false;
  Index num_non_finite_vertices = 0;   ///< vertices with a NaN/Inf coordinate (excluded below)
  Vec3 bbox_min = Vec3::Zero();        ///< axis-aligned bounding box of the finite vertices
  Vec3 bbox_max = Vec3::Zero();
  double max_extent = 0.0;             ///< largest bounding-box side, mesh units
  std::optional<EdgeLengthStats> edge_lengths;  ///< nullopt for a point cloud
  Index num_boundary_edges = 0;
  std::vector<BoundaryLoopStats> boundary_loops;  ///< by decreasing length
  Index num_components = 0;            ///< face-connected components (components.h)
  std::vector<Index> component_face_counts;  ///< triangles per component, largest first
  Index num_unreferenced_vertices = 0; ///< vertices no triangle uses (0 for a point cloud)
  Index num_degenerate_faces = 0;      ///< repeated index or zero area (cleanup.h)
  Index num_non_manifold_edges = 0;    ///< edges with 3+ triangles
  std::optional<Units> units;          ///< requested units, else detect_units' guess; nullopt if
                                       ///< the extent is ambiguous
  bool units_detected = false;         ///< true when `units` is a guess rather than requested
  std::string units_problem;           ///< why `units` is nullopt (detect_units' message)
  std::optional<double> max_extent_mm; ///< max_extent converted with `units`

  /// Multi-line human-readable report (one "key: value" per line).
  std::string full() const;
};

/// Computes the statistics.
/// \param[in] mesh   mesh or point cloud, in file units
/// \param[in] units  units of the mesh if known; nullopt = guess them (detect_units)
/// \throws InvalidInput if a triangle index is out of range
MeshStats mesh_stats(const TriangleMesh& mesh, std::optional<Units> units = std::nullopt);

}  // namespace breastfit::mesh
