#pragma once
/// \file Polylines lying exactly on a triangle mesh: chains of straight pieces, each inside one
/// triangle, traced as iso-lines of a per-vertex scalar or along mesh edges, then resampled into
/// SurfacePoints at a fixed spacing (the template's drawings).
#include <vector>

#include <Eigen/Core>

#include "breastfit/core/types.h"
#include "breastfit/mesh/surface_point.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::templ {

/// A straight piece from bary0 to bary1 inside triangle `face`.
struct PathSegment {
  Index face = 0;
  Vec3 bary0 = Vec3::Zero();
  Vec3 bary1 = Vec3::Zero();
};

/// Consecutive segments join end to start; a closed path ends where it starts.
struct SurfacePath {
  std::vector<PathSegment> segments;
  bool closed = false;
};

/// The level set {scalar = level} (scalar: one value per vertex, linear on each triangle) as
/// closed loops and open paths (ending on the mesh boundary). Vertices exactly at the level count
/// as above it. Deterministic order (by lowest triangle index).
/// \throws InvalidInput when scalar has the wrong size.
std::vector<SurfacePath> iso_lines(const TriangleMesh& mesh, const Eigen::VectorXd& scalar, double level);

/// A path along mesh edges through the given vertices (consecutive vertices must share an edge).
/// \throws InvalidInput when two consecutive vertices do not share an edge.
SurfacePath edge_path(const TriangleMesh& mesh, const std::vector<Index>& vertices);

/// Start and end positions, length, reversal and sub-paths.
Vec3 segment_point(const TriangleMesh& mesh, const PathSegment& s, double t);
double path_length(const TriangleMesh& mesh, const SurfacePath& path);
SurfacePath reversed(const SurfacePath& path);
/// Rotates a closed path so that it starts at the segment start nearest to `p`.
SurfacePath rotated_to_start_near(const TriangleMesh& mesh, const SurfacePath& path, const Vec3& p);

/// Points every `spacing` mm along the path (arc length). Open paths include both ends; closed
/// paths n points, the first at the start, none repeated at the end.
/// \throws InvalidInput when spacing <= 0 or the path is empty.
std::vector<SurfacePoint> resample_path(const TriangleMesh& mesh, const SurfacePath& path, double spacing);

}  // namespace breastfit::templ
