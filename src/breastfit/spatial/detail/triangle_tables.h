#pragma once
/// \file Per-triangle and per-vertex tables the spatial indices precompute at build time:
/// validation, degenerate/boundary flags, primitive boxes and a Morton order for batched queries
/// (private to the spatial layer; vertex normals come from mesh/normals.h).
#include <cstdint>
#include <string>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/spatial/closest_point_index.h"
#include "breastfit/spatial/detail/bvh.h"

namespace breastfit::spatial::detail {

inline constexpr std::uint8_t kFlagDegenerate = 1;      ///< zero-area (or nearly) triangle
inline constexpr std::uint8_t kFlagBoundaryEdge01 = 2;  ///< edge v0–v1 has one incident face
inline constexpr std::uint8_t kFlagBoundaryEdge12 = 4;  ///< edge v1–v2 has one incident face
inline constexpr std::uint8_t kFlagBoundaryEdge20 = 8;  ///< edge v2–v0 has one incident face

/// Throws InvalidInput (message prefixed by `who`) when the mesh has no triangles, a
/// non-finite vertex or a vertex index out of range.
void validate_triangle_mesh(const TriangleMesh& mesh, const std::string& who);

/// kFlag* bits per face. An edge is an open-boundary edge when exactly one face uses it
/// (whatever the orientation); edges shared by 2 or more faces are interior. When
/// `vertex_boundary` is given it receives 1 per vertex lying on such an edge, else 0 (#V).
/// `threads`: of the per-face loop (the result does not depend on it).
std::vector<std::uint8_t> triangle_flags(const TriangleMesh& mesh,
                                         std::vector<std::uint8_t>* vertex_boundary,
                                         int threads = 1);

/// Sets kFlagDegenerate in flags[f] (#F) where face f of `mesh` is degenerate
/// (is_degenerate_triangle) and clears it elsewhere; the other bits are kept. `threads`: of the
/// per-face loop (the result does not depend on it).
void mark_degenerate_faces(const TriangleMesh& mesh, std::vector<std::uint8_t>& flags, int threads = 1);

/// Axis-aligned box of every triangle (#F).
std::vector<PrimBox> triangle_boxes(const TriangleMesh& mesh);

/// True when `feature` of a face with `flags` and corners (v0, v1, v2) lies on an open
/// boundary: a boundary edge, or a vertex on a boundary edge. A Face feature never does.
bool feature_on_boundary(ClosestFeature feature, std::uint8_t flags, Index v0, Index v1,
                         Index v2, const std::vector<std::uint8_t>& vertex_boundary);

/// Faces sorted by the 63-bit Morton code (MortonGrid) of their box centres: the input of the
/// LBVH build. Same codes and order as Bvh::build(triangle_boxes(mesh)) uses, without the
/// boxes.
struct MortonSorted {
  std::vector<std::uint64_t> codes;  ///< ascending
  std::vector<std::uint32_t> prims;  ///< face of each code; ties by face index
};
/// `threads`: of the per-face loops (the result does not depend on it).
MortonSorted triangle_morton_order(const TriangleMesh& mesh, int threads = 1);

/// Row indices of P (#P by 3, finite) sorted along a 3D Morton (Z-order) curve over P's
/// bounding box, 21 bits per axis; ties by row index.
std::vector<std::uint32_t> morton_order(const Points& P);

}  // namespace breastfit::spatial::detail
