#include "breastfit/spatial/cell_grid.h"

#include <algorithm>
#include <cmath>

namespace breastfit::spatial {

CellGrid::CellGrid(const Points& points, double radius, int split)
    : points_(points), split_(split), cell_(radius / split * (1 + 1e-9)) {  // a hair wider: never a cell too few
  if (points.rows() == 0) return;
  lo_ = points.colwise().minCoeff().transpose();
  const Vec3 extent = points.colwise().maxCoeff().transpose() - lo_;
  for (int k = 0; k < 3; ++k) n_[k] = static_cast<Index>(std::floor(extent[k] / cell_)) + 1;
  std::vector<Index> cell(static_cast<size_t>(points.rows()));
  start_.assign(static_cast<size_t>(n_[0] * n_[1] * n_[2] + 1), 0);
  for (Index i = 0; i < points.rows(); ++i) {
    const auto c = cell_of(points.row(i).transpose());
    cell[static_cast<size_t>(i)] = (c[0] * n_[1] + c[1]) * n_[2] + c[2];
    ++start_[static_cast<size_t>(cell[static_cast<size_t>(i)]) + 1];
  }
  for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  order_.resize(static_cast<size_t>(points.rows()));
  std::vector<Index> fill(start_.begin(), start_.end() - 1);
  for (Index i = 0; i < points.rows(); ++i)
    order_[static_cast<size_t>(fill[static_cast<size_t>(cell[static_cast<size_t>(i)])]++)] = i;
}

void CellGrid::within(const Vec3& p, double radius, std::vector<Index>& nb, std::vector<double>& sq,
                      double min_sq) const {
  found_.clear();
  nb.clear();
  sq.clear();
  if (order_.empty()) return;
  const double r2 = radius * radius;
  std::array<Index, 3> from{}, to{};
  for (int k = 0; k < 3; ++k) {
    const double u = std::floor((p[k] - lo_[k]) / cell_);
    from[k] = static_cast<Index>(std::max(u - split_, 0.0));
    to[k] = static_cast<Index>(std::min(u + split_, static_cast<double>(n_[k] - 1)));
    if (u + split_ < 0 || u - split_ > static_cast<double>(n_[k] - 1)) return;
  }
  for (Index x = from[0]; x <= to[0]; ++x)
    for (Index y = from[1]; y <= to[1]; ++y) {
      const Index row = (x * n_[1] + y) * n_[2];
      for (Index k = start_[static_cast<size_t>(row + from[2])], e = start_[static_cast<size_t>(row + to[2] + 1)]; k < e;
           ++k) {
        const Index i = order_[static_cast<size_t>(k)];
        const double s = row_sq_dist(points_, i, p);
        if (s <= r2 && s >= min_sq) found_.emplace_back(s, i);
      }
    }
  std::sort(found_.begin(), found_.end());
  for (const auto& [s, i] : found_) {
    nb.push_back(i);
    sq.push_back(s);
  }
}

std::array<Index, 3> CellGrid::cell_of(const Vec3& p) const {
  std::array<Index, 3> c{};
  for (int k = 0; k < 3; ++k) c[k] = std::min(static_cast<Index>(std::floor((p[k] - lo_[k]) / cell_)), n_[k] - 1);
  return c;
}

}  // namespace breastfit::spatial
