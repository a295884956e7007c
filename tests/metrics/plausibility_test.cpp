#include "breastfit/metrics/plausibility.h"

#include <gtest/gtest.h>

#include "support/toy_model.h"

namespace breastfit::metrics {
namespace {

DistanceStats surface(double rmse) {
  DistanceStats s;
  s.n = 100;
  s.mae = 0.7 * rmse;
  s.rmse = rmse;
  return s;
}

bool mentions(const Plausibility& p, const std::string& text) {
  for (const auto& line : p.problems)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

TEST(Plausibility, ARestPoseWellCoveredIsPlausible) {
  const model::RiggedModel m = test::make_toy_model();
  model::PoseParams p = model::PoseParams::identity(m);
  for (auto& b : p.bones) b.scale = Vec3::Ones();  // strictly inside every bound
  const Plausibility j = judge_plausibility(m, p, 0.6, surface(1.5));
  EXPECT_TRUE(j.plausible) << (j.problems.empty() ? "" : j.problems.front());
  EXPECT_GT(j.bounded_parameters, 0);
}

TEST(Plausibility, EachSignIsNamed) {
  const model::RiggedModel m = test::make_toy_model();
  model::PoseParams p = model::PoseParams::identity(m);
  p.global.scale = 0.15;  // a torso at 0.15 of the template's size
  Plausibility j = judge_plausibility(m, p, 0.6, surface(1.5));
  EXPECT_FALSE(j.plausible);
  EXPECT_TRUE(mentions(j, "0.15 times the template's size")) << j.problems.front();

  p = model::PoseParams::identity(m);
  for (size_t b = 0; b < m.bones.size(); ++b) p.bones[b].scale = m.bones[b].scale_hi;  // every scale at its bound
  j = judge_plausibility(m, p, 0.6, surface(1.5));
  EXPECT_FALSE(j.plausible);
  EXPECT_TRUE(mentions(j, "ended at a bound")) << j.problems.front();
  EXPECT_GE(j.parameters_at_bound, 3 * static_cast<int>(m.bones.size()));
  EXPECT_EQ(j.at_bound.front(), m.bones.front().name + ".scale_x");

  j = judge_plausibility(m, model::PoseParams::identity(m), 0.05, surface(1.5));
  EXPECT_TRUE(mentions(j, "the scan covers 5 %"));
  j = judge_plausibility(m, model::PoseParams::identity(m), 0.6, surface(12.0));
  EXPECT_TRUE(mentions(j, "surface error RMSE 12.00 mm"));
  EXPECT_EQ(j.problems.size(), 1u);
}

}  // namespace
}  // namespace breastfit::metrics
