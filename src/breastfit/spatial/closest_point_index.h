#pragma once
/// \file Exact closest point on a triangle mesh (point-to-triangle, not nearest vertex).
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"

namespace breastfit::spatial {

/// Which feature of the triangle holds the closest point.
enum class ClosestFeature { Face, Edge01, Edge12, Edge20, Vertex0, Vertex1, Vertex2 };

struct ClosestPoint {
  Vec3 point = Vec3::Zero();   ///< closest point on the surface
  Index face = 0;              ///< triangle holding it
  Vec3 bary = Vec3::Zero();    ///< barycentric coordinates of `point` in `face`
  double sq_dist = 0.0;        ///< squared distance query→point
  ClosestFeature feature = ClosestFeature::Face;
  bool on_boundary = false;    ///< the closest feature is an open-boundary edge or vertex
  double distance() const;
};

/// Built once over a triangle mesh (BVH); queried many times, thread-safe for queries.
class ClosestPointIndex {
 public:
  /// \param threads  threads of the build (>= 1; the index is the same bits for any number)
  /// \throws InvalidInput when the mesh has no triangles or non-finite vertices.
  explicit ClosestPointIndex(const TriangleMesh& mesh, int threads = 1);
  /// Same index, taking over `mesh` instead of copying it (for callers that build a mesh only
  /// to index it). Addition, backwards compatible.
  explicit ClosestPointIndex(TriangleMesh&& mesh, int threads = 1);
  ~ClosestPointIndex();
  ClosestPointIndex(ClosestPointIndex&&) noexcept;
  ClosestPointIndex& operator=(ClosestPointIndex&&) noexcept;

  /// The same triangles at new positions V (#V by 3, as many rows as the mesh's): the tree keeps
  /// its leaves and its order, and their corners and boxes are refitted — a fraction of a build,
  /// with the answers of an index built on the moved mesh (the search is exact and its ties go to
  /// the lowest face whatever the tree); vertex and face normals, open-border flags and mesh()
  /// follow. Queries slow down as the boxes grow looser, the farther the vertices move from where
  /// the tree was built (a new index for a far move). Built anew where the tree cannot be kept
  /// (leaves stored in floats given positions that are not floats).
  /// \throws InvalidInput when V has another number of rows or a non-finite entry (the index is
  /// unchanged then).
  void move_vertices(const Points& V);
  /// move_vertices(V) given V's vertex normals as well (mesh::vertex_normals of the moved mesh,
  /// which the caller has computed: not computed again; they are what vertex_normals() and
  /// smooth_normal() use).
  /// \throws InvalidInput as move_vertices(V), or when `normals` is not #V by 3 and finite.
  void move_vertices(const Points& V, const Points& normals);

  /// Exact closest point to q.
  ClosestPoint closest(const Vec3& q) const;
  /// Closest point within max_dist of q, or nullopt (faster: prunes with the radius).
  std::optional<ClosestPoint> closest_within(const Vec3& q, double max_dist) const;

  /// closest() warm-started from a guess (e.g. last iteration's face for the same query):
  /// the distance to `hint_face` bounds the search from the start. Same result as closest(q)
  /// (ties still go to the lowest face index); only faster when the hint is good.
  /// An out-of-range hint is ignored. (Addition by the spatial helper, backwards compatible.)
  ClosestPoint closest(const Vec3& q, Index hint_face) const;
  /// closest_within() warm-started from `hint_face`; same result as without the hint.
  std::optional<ClosestPoint> closest_within(const Vec3& q, double max_dist,
                                             Index hint_face) const;
  /// Closest points of all rows of Q (#Q by 3), in input order; identical to calling closest()
  /// per row, but faster for many queries: processed in Morton (Z-curve) order, each query
  /// warm-started from the previous one's face. Single-threaded.
  /// \throws InvalidInput when a row is not finite (as closest() does for a non-finite q).
  std::vector<ClosestPoint> closest_batch(const Points& Q) const;

  /// The vertices of the mesh's triangles within `radius` of q (inclusive), by ascending index,
  /// each once, appended to `out` after clearing it. A vertex no triangle uses is never returned.
  /// For neighbourhoods of a surface point (e.g. the scan around a landmark) without a second
  /// index over the vertices: the tree's boxes prune, the leaves' own copies of their corners
  /// are tested. Addition, backwards compatible.
  /// \throws InvalidInput when q is not finite or radius is negative or not finite.
  void vertices_within(const Vec3& q, double radius, std::vector<Index>& out) const;

  /// Unit face normal of a triangle (zero for degenerate triangles).
  Vec3 face_normal(Index face) const;
  /// Area-weighted vertex normal interpolated at a closest point (smooth normal).
  Vec3 smooth_normal(const ClosestPoint& cp) const;
  /// The area-weighted unit vertex normals smooth_normal() interpolates (#V by 3; those of
  /// mesh::vertex_normals(mesh()), kept by the index). Addition, backwards compatible.
  const Points& vertex_normals() const;
  const TriangleMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Row indices of Q (#Q by 3, finite) in the order closest_batch() runs its queries: along a
/// Morton (Z-order) curve over Q's bounds, ties by row. Callers running many queries of their own
/// in this order find the index's nodes and leaves in the cache more often. Addition, backwards
/// compatible.
/// \throws InvalidInput when a row is not finite.
std::vector<std::uint32_t> query_order(const Points& Q);

}  // namespace breastfit::spatial
