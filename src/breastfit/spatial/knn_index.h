#pragma once
/// \file k-nearest-neighbour and radius queries on a fixed 3D point set (a k-d tree).
///
/// The k-d tree (nanoflann) is hidden behind PImpl: only knn_index.cpp includes it. Use it for
/// point-to-point neighbourhoods (normal estimation, sampling); for exact closest points on
/// triangles use closest_point_index.h.
///
/// Example:
/// \code
///   breastfit::spatial::KnnIndex index(scan.V);
///   std::vector<breastfit::Index> idx; std::vector<double> sq;
///   index.knn(query, 8, idx, sq);             // 8 nearest, ascending distance
/// \endcode
#include <memory>
#include <vector>

#include "breastfit/core/types.h"

namespace breastfit::spatial {

/// A nearest point: its index in the indexed set and its squared distance to the query.
struct Neighbor {
  Index index = 0;
  double sq_dist = 0.0;  ///< squared distance, squared point units
};

/// Built once over a copy of the points, then queried many times (const queries are thread-safe).
class KnnIndex {
 public:
  /// Builds the tree.
  /// \param[in] points  #P by 3 positions (copied)
  /// \throws InvalidInput if a coordinate is NaN or Inf
  explicit KnnIndex(const Points& points);
  ~KnnIndex();
  KnnIndex(KnnIndex&&) noexcept;
  KnnIndex& operator=(KnnIndex&&) noexcept;
  KnnIndex(const KnnIndex&) = delete;
  KnnIndex& operator=(const KnnIndex&) = delete;

  /// Number of indexed points (#P).
  Index size() const;
  /// The indexed points (#P by 3).
  const Points& points() const;

  /// The k nearest indexed points of `query`, by ascending distance (the query itself when it
  /// is an indexed point comes first). Returns fewer than k when #P < k.
  /// \param[in]  query     position
  /// \param[in]  k         number of neighbours, >= 1
  /// \param[out] indices   resized to min(k, #P)
  /// \param[out] sq_dists  squared distances, same size
  /// \throws InvalidInput if k < 1
  void knn(const Vec3& query, int k, std::vector<Index>& indices,
           std::vector<double>& sq_dists) const;

  /// The single nearest point.
  /// \throws InvalidInput if the index is empty
  Neighbor closest(const Vec3& query) const;

  /// Every indexed point within `radius` of `query` (inclusive), by ascending distance.
  /// \param[in] radius  in point units, >= 0
  /// \throws InvalidInput if radius is negative or not finite
  void radius_search(const Vec3& query, double radius, std::vector<Index>& indices,
                     std::vector<double>& sq_dists) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace breastfit::spatial
