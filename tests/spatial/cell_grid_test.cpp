// The cell grid's radius queries against the k-d tree's: the same neighbours in the same order
// (ascending squared distance) and the same squared distances, bit for bit; equal distances by index.
#include "breastfit/spatial/cell_grid.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "breastfit/spatial/knn_index.h"

namespace breastfit::spatial {
namespace {

TEST(CellGrid, GivesTheKdTreesNeighboursInItsOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  Points P(600, 3);
  for (Index i = 0; i < P.rows(); ++i) P.row(i) << u(rng), u(rng), 0.2 * u(rng);
  const KnnIndex tree(P);
  for (int split : {1, 2}) {
    const CellGrid grid(P, 8.0, split);
    std::vector<Index> nb, nb_tree;
    std::vector<double> sq, sq_tree;
    for (int q = 0; q < 50; ++q) {
      const Vec3 p = q == 0 ? Vec3(P.row(4).transpose()) : Vec3(u(rng), u(rng), u(rng));
      for (double r : {3.0, 8.0}) {
        grid.within(p, r, nb, sq);
        tree.radius_search(p, r, nb_tree, sq_tree);
        ASSERT_EQ(nb, nb_tree) << "split " << split << " query " << q << " radius " << r;
        ASSERT_EQ(sq, sq_tree);
      }
    }
  }
  // Equal distances come by index.
  Points T = P;
  T.row(5) = T.row(4);
  std::vector<Index> tie;
  std::vector<double> tie_sq;
  CellGrid(T, 8.0, 2).within(T.row(4).transpose(), 0.0, tie, tie_sq);
  ASSERT_EQ(tie.size(), 2u);
  EXPECT_EQ(tie[0], 4);
  EXPECT_EQ(tie[1], 5);
  // A query far outside the points' bounds finds nothing.
  std::vector<Index> nb;
  std::vector<double> sq;
  CellGrid(P, 8.0, 2).within(Vec3(500, 0, 0), 8.0, nb, sq);
  EXPECT_TRUE(nb.empty());
}

// A ring query (min_sq): exactly the whole ball's neighbours at least that far, in the ball's order,
// with the same squared distances — fit/nipple_bump.cpp sums the ring's points in that order.
TEST(CellGrid, ARingIsTheBallsNeighboursFromItsInnerRadiusOn) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  Points P(800, 3);
  for (Index i = 0; i < P.rows(); ++i) P.row(i) << u(rng), u(rng), 0.2 * u(rng);
  P.row(7) = P.row(3);  // a tie
  for (int split : {1, 2}) {
    const CellGrid grid(P, 16.0, split);
    std::vector<Index> nb, ring;
    std::vector<double> sq, ring_sq;
    for (int q = 0; q < 60; ++q) {
      const Vec3 p = q < 2 ? Vec3(P.row(3 + q).transpose()) : Vec3(u(rng), u(rng), u(rng));
      const double inner2 = q == 2 ? 0.0 : 64.0;
      grid.within(p, 16.0, nb, sq);
      grid.within(p, 16.0, ring, ring_sq, inner2);
      std::vector<Index> expected;
      std::vector<double> expected_sq;
      for (size_t j = 0; j < nb.size(); ++j)
        if (sq[j] >= inner2) {
          expected.push_back(nb[j]);
          expected_sq.push_back(sq[j]);
        }
      ASSERT_EQ(ring, expected) << "split " << split << " query " << q;
      ASSERT_EQ(ring_sq, expected_sq);
      if (q == 2) ASSERT_EQ(ring, nb);
    }
  }
}

}  // namespace
}  // namespace breastfit::spatial
