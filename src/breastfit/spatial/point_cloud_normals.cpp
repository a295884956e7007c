#include "breastfit/spatial/point_cloud_normals.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <functional>
#include <queue>
#include <string>
#include <vector>

#include "breastfit/core/errors.h"
#include "breastfit/spatial/knn_index.h"

namespace breastfit::spatial {

void PointCloudNormalsOptions::validate() const {
  if (num_neighbors < 3)
    throw InvalidInput("PointCloudNormalsOptions.num_neighbors = " + std::to_string(num_neighbors) +
                       " must be >= 3");
  if (viewpoint && !viewpoint->allFinite())
    throw InvalidInput("PointCloudNormalsOptions.viewpoint must be finite");
}

Points point_cloud_normals(const Points& P, const PointCloudNormalsOptions& options) {
  options.validate();
  const Index n = static_cast<Index>(P.rows());
  Points N = Points::Zero(n, 3);
  if (n == 0) return N;
  const KnnIndex index(P);  // throws on NaN/Inf
  const int k = std::min<int>(options.num_neighbors, n);

  // 1. PCA normals and the kNN graph.
  std::vector<std::vector<Index>> nbrs(static_cast<size_t>(n));
  std::vector<Index> idx;
  std::vector<double> sq;
  for (Index i = 0; i < n; ++i) {
    const Vec3 p = P.row(i).transpose();
    index.knn(p, k, idx, sq);
    Vec3 mean = Vec3::Zero();
    for (Index j : idx) mean += P.row(j).transpose();
    mean /= static_cast<double>(idx.size());
    Mat3 cov = Mat3::Zero();
    for (Index j : idx) {
      const Vec3 d = P.row(j).transpose() - mean;
      cov += d * d.transpose();
    }
    if (cov.trace() > 0.0) {
      Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);  // eigenvalues ascending
      N.row(i) = eig.eigenvectors().col(0).normalized().transpose();
    }
    nbrs[static_cast<size_t>(i)] = idx;
  }

  // 2. Orientation.
  if (options.viewpoint) {
    for (Index i = 0; i < n; ++i)
      if (N.row(i).dot(options.viewpoint->transpose() - P.row(i)) < 0.0) N.row(i) *= -1.0;
    return N;
  }
  const Eigen::RowVector3d centroid = P.colwise().mean();
  if (!options.propagate) {
    for (Index i = 0; i < n; ++i)
      if (N.row(i).dot(P.row(i) - centroid) < 0.0) N.row(i) *= -1.0;
    return N;
  }

  // Symmetric kNN graph.
  std::vector<std::vector<Index>> adj(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i)
    for (Index j : nbrs[static_cast<size_t>(i)])
      if (j != i) {
        adj[static_cast<size_t>(i)].push_back(j);
        adj[static_cast<size_t>(j)].push_back(i);
      }
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }

  // Seeds: points by decreasing distance from the centroid; each unvisited one starts a piece.
  std::vector<Index> order(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i) order[static_cast<size_t>(i)] = i;
  std::vector<double> dist_c(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i) dist_c[static_cast<size_t>(i)] = (P.row(i) - centroid).squaredNorm();
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) {
    return dist_c[static_cast<size_t>(a)] > dist_c[static_cast<size_t>(b)];
  });

  // Prim's algorithm: grow along the most parallel neighbours first, flipping to agree.
  using Item = std::pair<double, std::pair<Index, Index>>;  // (weight, (to, from))
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  std::vector<char> done(static_cast<size_t>(n), 0);
  // Hoppe's weight 1 - |n_i . n_j| plus how far the edge leaves the two tangent planes: two
  // nearby sheets facing each other (inner arm and chest wall) have parallel normals but are
  // joined along the normal, so they are linked last.
  auto edge_weight = [&](Index i, Index j) {
    const Eigen::RowVector3d e = P.row(j) - P.row(i);
    const double len = e.norm();
    const double off_plane =
        len > 0.0 ? 0.5 * (std::abs(N.row(i).dot(e)) + std::abs(N.row(j).dot(e))) / len : 0.0;
    return 1.0 - std::abs(N.row(i).dot(N.row(j))) + off_plane;
  };
  auto push_edges = [&](Index from) {
    for (Index to : adj[static_cast<size_t>(from)])
      if (!done[static_cast<size_t>(to)])
        heap.push({edge_weight(from, to), {to, from}});
  };
  for (Index seed : order) {
    if (done[static_cast<size_t>(seed)]) continue;
    if (N.row(seed).dot(P.row(seed) - centroid) < 0.0) N.row(seed) *= -1.0;
    done[static_cast<size_t>(seed)] = 1;
    push_edges(seed);
    while (!heap.empty()) {
      const auto [w, e] = heap.top();
      heap.pop();
      const auto [to, from] = e;
      if (done[static_cast<size_t>(to)]) continue;
      done[static_cast<size_t>(to)] = 1;
      if (N.row(to).dot(N.row(from)) < 0.0) N.row(to) *= -1.0;
      if (N.row(to).squaredNorm() > 0.0) push_edges(to);  // a zero normal carries no sign
    }
  }
  return N;
}

}  // namespace breastfit::spatial
