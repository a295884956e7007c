#pragma once
/// \file Radius queries over a small point set (a few hundred to a few thousand points) without a
/// tree: the points counting-sorted into a dense grid over their bounds, cells a `split`-th of the
/// query radius wide, so that a query reads the (2 split + 1)² runs of cells along z around its own.
/// The neighbours come by ascending squared distance, equal ones by index — where the distances
/// differ, the order and the squared distances spatial::KnnIndex gives, bit for bit (summed axis by
/// axis as there), so a caller can switch between the two without changing a sum. For one-off neighbourhoods where building a k-d tree
/// costs more than the queries (fit/nipple_bump.cpp: the scan's cells around a nipple).
#include <array>
#include <utility>
#include <vector>

#include "breastfit/core/types.h"

namespace breastfit::spatial {

/// Squared distance of row i of P to p, summed axis by axis (the order spatial::KnnIndex and
/// CellGrid sum it in: a pass over the rows that must give their bits uses this).
inline double row_sq_dist(const Points& P, Index i, const Vec3& p) {
  double s = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = p[k] - P(i, k);
    s += d * d;
  }
  return s;
}

class CellGrid {
 public:
  /// Grids `points` (kept by reference: they must outlive the grid) for queries of radius at most
  /// `radius` (> 0), in cells of radius / split (split >= 1).
  CellGrid(const Points& points, double radius, int split);

  /// The points within `radius` (<= the grid's radius) of p, inclusive, by ascending squared
  /// distance (`sq`) and index (`nb`). Not thread-safe (a scratch buffer per grid).
  /// With `min_sq`, only those whose squared distance is at least that (a ring: the same points,
  /// in the same order, as those of the whole ball that pass the test, without sorting the others).
  void within(const Vec3& p, double radius, std::vector<Index>& nb, std::vector<double>& sq,
              double min_sq = 0.0) const;

 private:
  std::array<Index, 3> cell_of(const Vec3& p) const;

  const Points& points_;
  int split_;
  double cell_;
  Vec3 lo_ = Vec3::Zero();
  std::array<Index, 3> n_{};
  std::vector<Index> start_;  // by cell (x, y, z → (x n_y + y) n_z + z): first slot of order_
  std::vector<Index> order_;  // the points by cell
  mutable std::vector<std::pair<double, Index>> found_;
};

}  // namespace breastfit::spatial
