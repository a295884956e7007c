#include "breastfit/spatial/cell_grid.h"

#include <algorithm>
#include <cmath>

namespace breastfit::spatial {
namespace {

// How much wider than the query's ball within() reads the cells, relatively and in cells² (the
// rounding of the points' cells and distances is ~1e-15 relatively).
constexpr double kReach = 1e-6;

}  // namespace

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
  Vec3 t;  // p in cells from lo_
  for (int k = 0; k < 3; ++k) {
    t[k] = (p[k] - lo_[k]) / cell_;
    const double u = std::floor(t[k]);
    from[k] = static_cast<Index>(std::max(u - split_, 0.0));
    to[k] = static_cast<Index>(std::min(u + split_, static_cast<double>(n_[k] - 1)));
    if (u + split_ < 0 || u - split_ > static_cast<double>(n_[k] - 1)) return;
  }
  // Of the (2 split + 1)³ cells around p's, only those the ball can reach: a column (x, y) whose
  // square is farther than the radius is skipped, and a column's run of cells along z is cut to the
  // ball's chord there. The test is in cells and a little wider (kReach) than the radius, so that
  // no point the distance test below keeps is skipped, whatever the rounding of the cells and of
  // the distances: the same points as the whole runs', sorted alike.
  const double reach2 = r2 / (cell_ * cell_) * (1 + kReach) + kReach;
  // How far p lies outside cell c along axis k, in cells (the last cell also holds what is beyond it).
  const auto gap = [&](int k, Index c) {
    const double above = c + 1 < n_[k] ? t[k] - static_cast<double>(c + 1) : 0.0;
    return std::max({static_cast<double>(c) - t[k], above, 0.0});
  };
  for (Index x = from[0]; x <= to[0]; ++x) {
    const double gx = gap(0, x);
    for (Index y = from[1]; y <= to[1]; ++y) {
      const double gy = gap(1, y);
      const double left2 = reach2 - gx * gx - gy * gy;
      if (left2 < 0) continue;
      const double chord = std::sqrt(left2);
      const Index z0 = std::max(from[2], static_cast<Index>(std::max(std::floor(t[2] - chord), -1.0)));
      const Index z1 = std::min(to[2], static_cast<Index>(std::min(std::floor(t[2] + chord), static_cast<double>(n_[2]))));
      if (z0 > z1) continue;
      const Index row = (x * n_[1] + y) * n_[2];
      for (Index k = start_[static_cast<size_t>(row + z0)], e = start_[static_cast<size_t>(row + z1 + 1)]; k < e; ++k) {
        const Index i = order_[static_cast<size_t>(k)];
        const double s = row_sq_dist(points_, i, p);
        if (s <= r2 && s >= min_sq) found_.emplace_back(s, i);
      }
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
