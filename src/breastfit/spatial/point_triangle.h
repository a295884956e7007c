#pragma once
/// \file Exact closest point on one triangle (Ericson's Voronoi-region method), with the
/// feature that holds it and its barycentric coordinates. Robust for needle and fully
/// degenerate (collinear or coincident-vertex) triangles.
#include "breastfit/core/types.h"
#include "breastfit/spatial/closest_point_index.h"

namespace breastfit::spatial {

/// Closest point of one triangle to a query point.
struct PointTriangleResult {
  Vec3 point = Vec3::Zero();  ///< closest point on the triangle (same units as the input, mm)
  Vec3 bary = Vec3::Zero();   ///< barycentrics of `point` w.r.t. (a, b, c); >= 0, sum 1
  double sq_dist = 0.0;       ///< squared distance p→point (mm²)
  /// Face, an edge (Edge01 = a–b, Edge12 = b–c, Edge20 = c–a) or a vertex (Vertex0 = a, …).
  ClosestFeature feature = ClosestFeature::Face;
};

/// Exact closest point on triangle (a, b, c) to p.
///
/// Uses the region tests of Ericson, *Real-Time Collision Detection* (2005), §5.1.5, in double
/// precision. When the triangle is degenerate or so thin that the face solve is ill-conditioned
/// (sin² of its widest angle below 1e-12), the answer is the closest of its three edges
/// (a zero-length edge reports its first vertex). Barycentrics of the coordinate not on the
/// reported feature are exactly zero (e.g. bary[2] == 0 for Edge01, bary == (1,0,0) for Vertex0).
///
/// \param[in] p query point
/// \param[in] a,b,c triangle corners (counter-clockwise = outward; orientation does not matter)
/// \pre all inputs finite.
PointTriangleResult closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                              const Vec3& c);

/// Same as closest_point_on_triangle() but from raw coordinates (3 doubles each); the hot path
/// of ClosestPointIndex. Writes bary and feature and returns the squared distance; the closest
/// point is bary[0]*a + bary[1]*b + bary[2]*c.
double closest_point_on_triangle(const double* p, const double* a, const double* b,
                                 const double* c, double* bary, ClosestFeature* feature);

/// True when `feature` is one of the three vertices.
bool is_vertex_feature(ClosestFeature feature);
/// True when `feature` is one of the three edges.
bool is_edge_feature(ClosestFeature feature);

}  // namespace breastfit::spatial
