// The cell grid's radius queries against the k-d tree's: the same neighbours in the same order
// (ascending squared distance) and the same squared distances, bit for bit; equal distances by index.
#include "breastfit/spatial/cell_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>
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

// Every point whose squared distance passes the test, however near the ball's surface or the
// cells' corners: within() reads only the cells the ball can reach, never one holding such a point.
// Points on spheres of the query radius around queries on the cells' corners, edges and faces,
// and jittered by a few ulps, against a pass over every point (the same test, sorted alike).
TEST(CellGrid, ReadsEveryPointTheBallHoldsAtItsSurface) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double grid_radius = 16.0;
  for (int split : {1, 2, 3}) {
    const double cell = grid_radius / split * (1 + 1e-9);  // the grid's cells (cell_grid.cpp)
    std::vector<Vec3> queries;
    for (const Vec3 c : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(1, 1, 1), Vec3(0.5, 0.5, 0.5)})
      queries.push_back(Vec3(-40, -40, -40) + 3 * cell * Vec3::Ones() + cell * c);
    for (int q = 0; q < 10; ++q) queries.push_back(Vec3(-40, -40, -40) + Vec3(30 + 20 * unit(rng), 30 + 20 * unit(rng), 30 + 20 * unit(rng)));
    for (const Vec3& p : queries)
      for (const double r : {grid_radius, 0.5 * grid_radius, 0.37 * grid_radius}) {
        // The bounds' corner first (the grid's lo), then points on the sphere of radius r around p,
        // some on it exactly along the axes and diagonals, the others a few ulps inside or outside.
        std::vector<Vec3> pts{Vec3(-40, -40, -40), Vec3(60, 60, 60)};
        for (int k = 0; k < 3; ++k)
          for (const double sgn : {-1.0, 1.0}) pts.push_back(p + sgn * r * Vec3::Unit(k));
        for (int k = 0; k < 400; ++k) {
          const Vec3 d = Vec3(unit(rng), unit(rng), unit(rng)).normalized();
          const double scale = 1 + (k % 5 - 2) * 1e-15;
          pts.push_back(p + r * scale * d);
        }
        Points P(static_cast<Index>(pts.size()), 3);
        for (size_t i = 0; i < pts.size(); ++i) P.row(static_cast<Index>(i)) = pts[i].transpose();
        const CellGrid grid(P, grid_radius, split);
        for (const double min_sq : {0.0, 0.25 * r * r}) {
          std::vector<Index> nb;
          std::vector<double> sq;
          grid.within(p, r, nb, sq, min_sq);
          std::vector<std::pair<double, Index>> all;
          for (Index i = 0; i < P.rows(); ++i) {
            const double s = row_sq_dist(P, i, p);
            if (s <= r * r && s >= min_sq) all.emplace_back(s, i);
          }
          std::sort(all.begin(), all.end());
          ASSERT_EQ(nb.size(), all.size()) << "split " << split << " radius " << r << " query " << p.transpose();
          for (size_t j = 0; j < all.size(); ++j) {
            ASSERT_EQ(nb[j], all[j].second);
            ASSERT_EQ(sq[j], all[j].first);
          }
          EXPECT_GT(nb.size(), 100u);  // the sphere's points near the ball's surface are there
        }
      }
  }
}

}  // namespace
}  // namespace breastfit::spatial
