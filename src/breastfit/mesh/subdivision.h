#pragma once
/// \file 1-to-4 triangle subdivision (Loop or midpoint) that keeps track of surface points, used
/// to refine the posed template (~16 mm edges) into the dense truth surface (~2 mm edges).
#include "breastfit/core/types.h"
#include "breastfit/mesh/surface_point.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::mesh {

/// One subdivision step: every triangle (v0, v1, v2) with edge points m01, m12, m20 becomes the
/// four triangles 4f+0 = (v0, m01, m20), 4f+1 = (v1, m12, m01), 4f+2 = (v2, m20, m12),
/// 4f+3 = (m01, m12, m20), keeping the orientation. Vertex i of the input stays vertex i; edge
/// points follow, in order of their sorted (min, max) vertex pair.
/// Loop (loop = true): interior edge points 3/8 (a + b) + 1/8 (c + d), interior vertices with
/// Warren's weights (β = 3/16 for valence 3, else 3/(8n)); on open borders the boundary curve is
/// subdivided as a cubic B-spline (3/4 v + 1/8 neighbours, edge midpoints); vertices on
/// non-manifold edges or pinched borders stay put. Midpoint (loop = false): edge midpoints, vertices
/// unchanged (the surface does not change).
/// \param[in] mesh  triangle mesh (V, F); attributes other than V and F are dropped
/// \throws InvalidInput if an index is out of range
TriangleMesh subdivide(const TriangleMesh& mesh, bool loop);

/// The same parametric point after one subdivide() step: the child triangle of p.face that
/// contains p.bary in the 1-to-4 split and the barycentric coordinates in that child.
SurfacePoint refine_surface_point(const SurfacePoint& p);

/// Median edge length of a triangle mesh (each undirected edge counted once per triangle side),
/// in mesh units; 0 for a mesh without triangles.
double median_edge_length(const TriangleMesh& mesh);

}  // namespace breastfit::mesh
