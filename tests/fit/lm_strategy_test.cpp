#include "breastfit/fit/lm_strategy.h"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace breastfit::fit {
namespace {

TEST(LevenbergMarquardtStrategy, PredictsTheExactDecreaseOfAQuadratic) {
  // E(δ) = E0 + 2gᵀδ + δᵀHδ exactly: the gain ratio of any step is 1.
  Eigen::MatrixXd H(2, 2);
  H << 4, 1, 1, 3;
  const Eigen::VectorXd g = Eigen::Vector2d(1, -2);
  SolverOptions o;
  o.initial_damping = 1e-9;
  o.min_damping = 1e-12;
  LevenbergMarquardtStrategy s(o);
  const LmStep step = s.compute_step(H, g);
  ASSERT_TRUE(step.ok);
  const Eigen::VectorXd newton = H.ldlt().solve(-g);
  EXPECT_LT((step.x - newton).norm(), 1e-6);
  const double actual = -(2 * g.dot(step.x) + step.x.dot(H * step.x));
  EXPECT_NEAR(step.predicted_decrease, actual, 1e-12);
  EXPECT_GT(step.predicted_decrease, 0);
}

TEST(LevenbergMarquardtStrategy, MoreDampingGivesAShorterStep) {
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(3, 3) * 2;
  const Eigen::VectorXd g = Eigen::Vector3d(1, 1, 1);
  SolverOptions weak, strong;
  strong.initial_damping = 10.0;
  LevenbergMarquardtStrategy a(weak), b(strong);
  EXPECT_GT(a.compute_step(H, g).x.norm(), b.compute_step(H, g).x.norm() * 5);
}

TEST(LevenbergMarquardtStrategy, UpdatesTheDampingFromTheGainRatio) {
  SolverOptions o;
  o.initial_damping = 1.0;
  o.good_gain_ratio = 0.25;
  o.damping_decrease = 3.0;
  o.damping_increase = 5.0;
  LevenbergMarquardtStrategy s(o);
  s.step_accepted(0.9);  // a good step: μ/3
  EXPECT_NEAR(s.damping(), 1.0 / 3.0, 1e-15);
  s.step_accepted(0.1);  // accepted, but the model was poor: μ kept
  EXPECT_NEAR(s.damping(), 1.0 / 3.0, 1e-15);
  s.step_rejected();  // ×5
  EXPECT_NEAR(s.damping(), 5.0 / 3.0, 1e-12);
  s.reset();
  EXPECT_EQ(s.damping(), 1.0);
  o.good_gain_ratio = 0.0;  // the default: every accepted step lowers μ
  s.step_accepted(0.01);
  EXPECT_NEAR(s.damping(), 1.0 / 3.0, 1e-15);
}

TEST(LevenbergMarquardtStrategy, StaysWithinItsBoundsAndSaysWhenExhausted) {
  SolverOptions o;
  o.initial_damping = 1.0;
  o.min_damping = 0.5;
  o.max_damping = 10.0;
  LevenbergMarquardtStrategy s(o);
  for (int i = 0; i < 5; ++i) s.step_accepted(1.0);
  EXPECT_EQ(s.damping(), 0.5);
  EXPECT_FALSE(s.exhausted());
  for (int i = 0; i < 10; ++i) s.step_rejected();
  EXPECT_EQ(s.damping(), 10.0);
  EXPECT_TRUE(s.exhausted());
}

TEST(LevenbergMarquardtStrategy, ANonFiniteSystemFailsAndRaisesTheDamping) {
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  H(0, 0) = NAN;
  SolverOptions o;
  LevenbergMarquardtStrategy s(o);
  const LmStep step = s.compute_step(H, Eigen::Vector2d(1, 1));
  EXPECT_FALSE(step.ok);
  EXPECT_GT(s.damping(), o.initial_damping);
}

}  // namespace
}  // namespace breastfit::fit
