#pragma once
/// \file Normals of a point cloud (a vertex-only PLY scan): PCA of each point's k nearest
/// neighbours, then a consistent orientation.
///
/// The unoriented normal of a point is the eigenvector of the smallest eigenvalue of the
/// covariance of its k nearest neighbours (itself included). Orientation (the sign), in order:
///  - `viewpoint` given: every normal points towards the viewpoint (the scanner position), the
///    usual choice when the acquisition position is known;
///  - otherwise: the outward sign is propagated over a minimum spanning tree of the kNN graph
///    weighted by 1 - |n_i . n_j| (Hoppe et al. 1992) plus the mean |n . e| of the unit edge
///    direction e (so that two close sheets facing each other, such as the inner arm and the
///    chest wall, are joined last), seeded in each connected piece at the point
///    farthest from the cloud's centroid, whose normal is oriented away from the centroid. For a
///    torso (closed or front-only) this points the normals out of the body; without propagation
///    (`propagate = false`) each normal simply points away from the centroid.
///
/// Measured on the benchmark scans (p0 standing / supine, 73-89k points, k = 16): median angle to
/// the scan mesh's own vertex normals 11-13 deg; clearly flipped (dot < -0.5) normals on the main
/// body piece 0.4 % / 0.3 % with propagation, 3.6 % / 5.4 % away-from-centroid only; ~1.3 s.
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::spatial {

struct PointCloudNormalsOptions {
  int num_neighbors = 16;          ///< k of the PCA neighbourhood (itself included), >= 3
  std::optional<Vec3> viewpoint;   ///< orient towards this point (same frame/units as the cloud)
  bool propagate = true;           ///< without viewpoint: MST propagation (true) or the plain
                                   ///< away-from-centroid sign per point (false)

  /// \throws InvalidInput naming the field, value and rule
  void validate() const;
};

/// Estimates oriented unit normals of a point cloud.
/// \param[in] P        #P by 3 positions (any units)
/// \param[in] options  see PointCloudNormalsOptions
/// \return #P by 3 unit rows; a zero row where the neighbourhood is degenerate (all its points
///         coincide)
/// \throws InvalidInput for invalid options or a NaN/Inf coordinate
Points point_cloud_normals(const Points& P, const PointCloudNormalsOptions& options = {});

}  // namespace breastfit::spatial
