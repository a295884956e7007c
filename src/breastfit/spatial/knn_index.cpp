#include "breastfit/spatial/knn_index.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "breastfit/core/errors.h"

namespace breastfit::spatial {
namespace {

/// nanoflann dataset adaptor over a row-major #P by 3 matrix.
struct PointsAdaptor {
  const Points* P = nullptr;
  size_t kdtree_get_point_count() const { return static_cast<size_t>(P->rows()); }
  double kdtree_get_pt(size_t i, size_t dim) const {
    return (*P)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(dim));
  }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointsAdaptor>,
                                                 PointsAdaptor, 3, std::uint32_t>;

}  // namespace

struct KnnIndex::Impl {
  Points points;
  PointsAdaptor adaptor;
  std::unique_ptr<Tree> tree;  // refers to `adaptor`, which refers to `points`: Impl never moves
};

KnnIndex::KnnIndex(const Points& points) : impl_(std::make_unique<Impl>()) {
  if (!points.allFinite()) {
    for (Eigen::Index i = 0; i < points.rows(); ++i)
      if (!points.row(i).allFinite())
        throw InvalidInput("KnnIndex: point " + std::to_string(i) + " has a NaN or Inf coordinate");
  }
  impl_->points = points;
  impl_->adaptor.P = &impl_->points;
  impl_->tree = std::make_unique<Tree>(3, impl_->adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  if (points.rows() > 0) impl_->tree->buildIndex();
}

KnnIndex::~KnnIndex() = default;
KnnIndex::KnnIndex(KnnIndex&&) noexcept = default;
KnnIndex& KnnIndex::operator=(KnnIndex&&) noexcept = default;

Index KnnIndex::size() const { return static_cast<Index>(impl_->points.rows()); }

const Points& KnnIndex::points() const { return impl_->points; }

void KnnIndex::knn(const Vec3& query, int k, std::vector<Index>& indices,
                   std::vector<double>& sq_dists) const {
  if (k < 1) throw InvalidInput("KnnIndex::knn: k = " + std::to_string(k) + " must be >= 1");
  indices.clear();
  sq_dists.clear();
  const size_t n = static_cast<size_t>(impl_->points.rows());
  if (n == 0) return;
  const size_t want = std::min(static_cast<size_t>(k), n);
  std::vector<std::uint32_t> idx(want);
  sq_dists.resize(want);
  const double q[3] = {query.x(), query.y(), query.z()};
  const size_t found = impl_->tree->knnSearch(q, want, idx.data(), sq_dists.data());
  sq_dists.resize(found);
  indices.resize(found);
  for (size_t i = 0; i < found; ++i) indices[i] = static_cast<Index>(idx[i]);
}

Neighbor KnnIndex::closest(const Vec3& query) const {
  if (impl_->points.rows() == 0) throw InvalidInput("KnnIndex::closest: the index is empty");
  std::uint32_t i = 0;
  double d = 0.0;
  const double q[3] = {query.x(), query.y(), query.z()};
  impl_->tree->knnSearch(q, 1, &i, &d);
  return {static_cast<Index>(i), d};
}

void KnnIndex::radius_search(const Vec3& query, double radius, std::vector<Index>& indices,
                             std::vector<double>& sq_dists) const {
  if (!(radius >= 0.0) || !std::isfinite(radius))
    throw InvalidInput("KnnIndex::radius_search: radius = " + std::to_string(radius) +
                       " must be finite and >= 0");
  indices.clear();
  sq_dists.clear();
  if (impl_->points.rows() == 0) return;
  std::vector<std::pair<std::uint32_t, double>> found;
  const double q[3] = {query.x(), query.y(), query.z()};
  nanoflann::SearchParams params;
  params.sorted = true;
  // nanoflann's L2 metric works on squared distances; it keeps d < r^2 — nudge so the radius is
  // inclusive.
  const double r2 = radius * radius;
  impl_->tree->radiusSearch(q, std::nextafter(r2, std::numeric_limits<double>::infinity()), found,
                            params);
  indices.reserve(found.size());
  sq_dists.reserve(found.size());
  for (const auto& [i, d] : found) {
    if (d > r2) continue;
    indices.push_back(static_cast<Index>(i));
    sq_dists.push_back(d);
  }
}

}  // namespace breastfit::spatial
