#pragma once
/// \file Face normals, face areas and area-weighted vertex normals of a triangle mesh.
///
/// Units-agnostic: areas are in squared mesh units, normals are unit vectors. A triangle's normal
/// follows its winding (counter-clockwise seen from outside = outward).
///
/// One rule for what has no normal: a face or vertex normal is a zero row when the cross product
/// it normalises (the face's, or the sum over a vertex's triangles) has zero or non-finite
/// length — a degenerate (zero-area) triangle, a vertex no triangle of non-zero area uses
/// (isolated vertices, every vertex of a point cloud), or overflowing/NaN coordinates. Callers
/// that need a unit vector everywhere substitute their own fallback for zero rows.
///
/// Example:
/// \code
///   breastfit::Points N = breastfit::mesh::vertex_normals(scan);   // #V by 3, unit rows
/// \endcode
#include <Eigen/Core>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::mesh {

/// Unit normal of every triangle, (v1 - v0) x (v2 - v0) normalised.
/// \param[in] V  #V by 3 vertex positions
/// \param[in] F  #F by 3 vertex indices (in range)
/// \return #F by 3; a zero row for a degenerate (zero-area) triangle (see the file comment)
Points face_normals(const Points& V, const Triangles& F);
Points face_normals(const TriangleMesh& mesh);

/// Area of every triangle (half the norm of the edge cross product).
/// \return #F vector, squared mesh units
Eigen::VectorXd face_areas(const Points& V, const Triangles& F);
Eigen::VectorXd face_areas(const TriangleMesh& mesh);

/// Area-weighted vertex normals: each vertex normal is the normalised sum of the (unnormalised)
/// cross products of its incident triangles, i.e. the face normals weighted by face area.
/// \param[in] V  #V by 3 vertex positions
/// \param[in] F  #F by 3 vertex indices (in range)
/// \return #V by 3 unit rows; a zero row for a vertex with no incident triangle of non-zero area
///         (see the file comment; for point clouds see spatial/point_cloud_normals.h)
/// \throws InvalidInput if an index of F is out of range
Points vertex_normals(const Points& V, const Triangles& F);
Points vertex_normals(const TriangleMesh& mesh);

}  // namespace breastfit::mesh
