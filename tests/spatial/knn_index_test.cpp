#include "breastfit/spatial/knn_index.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>

#include "breastfit/core/errors.h"
#include "breastfit/core/rng.h"

namespace breastfit::spatial {
namespace {

Points random_points(int n, std::uint64_t seed, double scale = 100.0) {
  Rng rng(seed);
  Points P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) << rng.uniform(-scale, scale), rng.uniform(-scale, scale), rng.uniform(-scale, scale);
  return P;
}

std::vector<double> brute_sq_dists(const Points& P, const Vec3& q) {
  std::vector<double> d(static_cast<size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) d[static_cast<size_t>(i)] = (P.row(i).transpose() - q).squaredNorm();
  return d;
}

TEST(KnnIndex, KnnMatchesBruteForce) {
  const Points P = random_points(2000, 7);
  const KnnIndex index(P);
  EXPECT_EQ(index.size(), 2000);
  const Points Q = random_points(200, 8, 120.0);
  std::vector<Index> idx;
  std::vector<double> sq;
  for (Eigen::Index q = 0; q < Q.rows(); ++q) {
    const Vec3 query = Q.row(q).transpose();
    index.knn(query, 10, idx, sq);
    ASSERT_EQ(idx.size(), 10u);
    std::vector<double> all = brute_sq_dists(P, query);
    std::vector<double> sorted = all;
    std::sort(sorted.begin(), sorted.end());
    for (size_t k = 0; k < 10; ++k) {
      EXPECT_DOUBLE_EQ(sq[k], sorted[k]) << "query " << q << " rank " << k;
      EXPECT_DOUBLE_EQ(all[static_cast<size_t>(idx[k])], sq[k]);
    }
    const Neighbor nn = index.closest(query);
    EXPECT_DOUBLE_EQ(nn.sq_dist, sorted[0]);
    EXPECT_EQ(nn.index, idx[0]);
  }
}

TEST(KnnIndex, IndexedPointIsItsOwnNearest) {
  const Points P = random_points(500, 3);
  const KnnIndex index(P);
  for (Index i = 0; i < 500; i += 37) {
    const Neighbor nn = index.closest(P.row(i).transpose());
    EXPECT_EQ(nn.index, i);
    EXPECT_EQ(nn.sq_dist, 0.0);
  }
}

TEST(KnnIndex, RadiusSearchMatchesBruteForceInclusive) {
  const Points P = random_points(1500, 11);
  const KnnIndex index(P);
  std::vector<Index> idx;
  std::vector<double> sq;
  const Vec3 q(5, -3, 10);
  const double r = 40.0;
  index.radius_search(q, r, idx, sq);
  const auto all = brute_sq_dists(P, q);
  std::vector<Index> expected;
  for (size_t i = 0; i < all.size(); ++i)
    if (all[i] <= r * r) expected.push_back(static_cast<Index>(i));
  std::vector<Index> got = idx;
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, expected);
  EXPECT_TRUE(std::is_sorted(sq.begin(), sq.end()));
  // Inclusive at exactly the radius.
  Points two(2, 3);
  two << 0, 0, 0, 3, 4, 0;
  const KnnIndex small(two);
  small.radius_search(Vec3::Zero(), 5.0, idx, sq);
  EXPECT_EQ(idx.size(), 2u);
  small.radius_search(Vec3::Zero(), 4.999, idx, sq);
  EXPECT_EQ(idx.size(), 1u);
}

TEST(KnnIndex, FewerPointsThanKAndEmpty) {
  Points P(3, 3);
  P << 0, 0, 0, 1, 0, 0, 5, 0, 0;
  const KnnIndex index(P);
  std::vector<Index> idx;
  std::vector<double> sq;
  index.knn(Vec3(0.9, 0, 0), 10, idx, sq);
  EXPECT_EQ(idx, (std::vector<Index>{1, 0, 2}));
  const KnnIndex empty{Points(0, 3)};
  EXPECT_EQ(empty.size(), 0);
  empty.knn(Vec3::Zero(), 3, idx, sq);
  EXPECT_TRUE(idx.empty());
  EXPECT_THROW(empty.closest(Vec3::Zero()), InvalidInput);
}

TEST(KnnIndex, BadInputsThrow) {
  Points P = random_points(10, 1);
  P(4, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(KnnIndex{P}, InvalidInput);
  const KnnIndex ok(random_points(10, 2));
  std::vector<Index> idx;
  std::vector<double> sq;
  EXPECT_THROW(ok.knn(Vec3::Zero(), 0, idx, sq), InvalidInput);
  EXPECT_THROW(ok.radius_search(Vec3::Zero(), -1.0, idx, sq), InvalidInput);
}

TEST(KnnIndex, MoveKeepsIndexUsable) {
  const Points P = random_points(100, 5);
  KnnIndex a(P);
  KnnIndex b = std::move(a);
  EXPECT_EQ(b.size(), 100);
  EXPECT_EQ(b.closest(P.row(42).transpose()).index, 42);
  EXPECT_EQ(b.points(), P);
}

}  // namespace
}  // namespace breastfit::spatial
