#include "breastfit/fit/normal_equations.h"

#include <gtest/gtest.h>

#include "breastfit/core/rng.h"

namespace breastfit::fit {
namespace {

TEST(NormalEquations, MatchesDenseJacobianProducts) {
  const int n = 7;
  Rng rng(3);
  NormalEquations eq(n);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(5, n);
  Eigen::VectorXd r(5), w(5);
  for (int row = 0; row < 5; ++row) {
    std::vector<int> idx{row % n, (row + 2) % n, (row + 5) % n};
    std::vector<double> val{rng.normal(), rng.normal(), rng.normal()};
    for (int k = 0; k < 3; ++k) J(row, idx[k]) += val[k];
    r[row] = rng.normal();
    w[row] = rng.uniform(0.1, 2.0);
    eq.add_row(idx.data(), val.data(), 3, r[row], w[row]);
  }
  eq.finalize();
  const Eigen::MatrixXd H = J.transpose() * w.asDiagonal() * J;
  const Eigen::VectorXd g = J.transpose() * w.asDiagonal() * r;
  EXPECT_LT((eq.H() - H).norm(), 1e-12);
  EXPECT_LT((eq.g() - g).norm(), 1e-12);
  EXPECT_NEAR(eq.cost(), (w.array() * r.array().square()).sum(), 1e-12);
  eq.clear();
  EXPECT_EQ(eq.H().norm(), 0.0);
  EXPECT_EQ(eq.cost(), 0.0);
}

TEST(NormalEquations, ActiveSubsetMatchesTheSubmatrix) {
  const int n = 9;
  Rng rng(8);
  NormalEquations full(n), sub(n);
  const std::vector<int> active{1, 4, 5, 8};
  sub.set_active(active);
  for (int row = 0; row < 200; ++row) {  // more rows than one buffered block
    std::vector<int> idx{row % n, (row * 3 + 1) % n, (row * 7 + 2) % n};
    if (idx[1] == idx[0]) idx[1] = (idx[1] + 1) % n;
    if (idx[2] == idx[0] || idx[2] == idx[1]) idx.pop_back();
    std::vector<double> val;
    for (size_t k = 0; k < idx.size(); ++k) val.push_back(rng.normal());
    const double r = rng.normal(), w = rng.uniform(0.5, 1.5);
    full.add_row(idx.data(), val.data(), static_cast<int>(idx.size()), r, w);
    sub.add_row(idx.data(), val.data(), static_cast<int>(idx.size()), r, w);
  }
  full.finalize();
  sub.finalize();
  ASSERT_EQ(sub.size(), 4);
  for (int a = 0; a < 4; ++a) {
    EXPECT_NEAR(sub.g()[a], full.g()[active[a]], 1e-10);
    for (int b = 0; b < 4; ++b) EXPECT_NEAR(sub.H()(a, b), full.H()(active[a], active[b]), 1e-10);
  }
  EXPECT_NEAR(sub.cost(), full.cost(), 1e-10);
}

TEST(NormalEquations, AnyActiveTellsWhetherARangeHasAnActiveParameter) {
  NormalEquations eq(9);
  EXPECT_TRUE(eq.any_active(0, 9));
  eq.set_active({1, 4, 5});
  EXPECT_TRUE(eq.any_active(4, 9));
  EXPECT_TRUE(eq.any_active(0, 2));
  EXPECT_FALSE(eq.any_active(6, 9));
  EXPECT_FALSE(eq.any_active(2, 4));
  EXPECT_FALSE(eq.any_active(5, 5));  // empty range
  EXPECT_FALSE(eq.any_active(7, 20));  // beyond the parameters
}

}  // namespace
}  // namespace breastfit::fit
