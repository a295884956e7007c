#pragma once
/// \file Exact point queries on a small triangle mesh (brute force, deterministic): closest
/// surface point and first ray hit, returned as SurfacePoint (face + barycentrics).
#include <optional>

#include "breastfit/core/types.h"
#include "breastfit/mesh/surface_point.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::templ {

/// Closest point of the mesh to q (ties: lowest face index), by spatial::closest_point_on_triangle
/// on every triangle (degenerate triangles answer with their closest edge).
/// \throws InvalidInput when the mesh has no triangles.
SurfacePoint closest_surface_point(const TriangleMesh& mesh, const Vec3& q);

/// First intersection of the ray origin + t dir (t in (0, max_t]) with the mesh, or nullopt.
std::optional<SurfacePoint> first_ray_hit(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir,
                                          double max_t);

}  // namespace breastfit::templ
