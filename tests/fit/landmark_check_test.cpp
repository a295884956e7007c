#include "breastfit/fit/landmark_check.h"

#include <gtest/gtest.h>

#include "breastfit/fit/registration.h"
#include "breastfit/model/pose_evaluator.h"
#include "support/toy_model.h"

namespace breastfit::fit {
namespace {

TEST(LandmarkCheck, ToleranceIsWiderForTheLineLandmarks) {
  EXPECT_DOUBLE_EQ(landmark_check_tolerance_mm("nipple_R", 15.0), 15.0);
  EXPECT_DOUBLE_EQ(landmark_check_tolerance_mm("lowest_breast_L", 15.0), 15.0);
  EXPECT_DOUBLE_EQ(landmark_check_tolerance_mm("midaxillary_L", 15.0), 30.0);
}

TEST(LandmarkCheck, RobustFactorIsOneWithinTheToleranceAndFadesBeyond) {
  EXPECT_EQ(robust_landmark_factor(0.0, 15.0), 1.0);
  EXPECT_EQ(robust_landmark_factor(15.0, 15.0), 1.0);
  EXPECT_DOUBLE_EQ(robust_landmark_factor(30.0, 15.0), 0.25);
  EXPECT_DOUBLE_EQ(robust_landmark_factor(150.0, 15.0), 0.01);
  // The weighted squared residual w·d² stays bounded by tolerance² beyond the tolerance.
  EXPECT_DOUBLE_EQ(robust_landmark_factor(60.0, 15.0) * 60.0 * 60.0, 225.0);
}

struct ToyScan {
  model::RiggedModel m = test::make_toy_model();
  model::PoseParams truth = test::random_toy_pose(m, 31, 0.4);
  TriangleMesh mesh = [&] {
    TriangleMesh t;
    t.V = model::pose_vertices(m, truth);
    t.F = m.rest.F;
    return t;
  }();
  std::vector<std::pair<std::string, Vec3>> landmarks() const {
    std::vector<std::pair<std::string, Vec3>> named;
    for (const auto& lm : m.landmarks) named.emplace_back(lm.name, lm.point.position(mesh.V, m.rest.F));
    return named;
  }
};

const LandmarkCheck* find(const FitSummary& s, const std::string& name) {
  for (const auto& c : s.landmark_checks)
    if (c.name == name) return &c;
  return nullptr;
}

TEST(LandmarkCheck, LandmarksAsPlacedAreNotFlagged) {
  ToyScan c;
  ScanTarget scan(c.mesh, 300);
  const FitResult r = register_template(c.m, scan, match_landmarks(c.m, c.landmarks()), FitOptions{});
  ASSERT_EQ(r.summary.landmark_checks.size(), c.m.landmarks.size());
  for (const auto& check : r.summary.landmark_checks) {
    EXPECT_FALSE(check.flagged) << check.name << " " << check.distance_mm;
    EXPECT_EQ(check.factor, 1.0) << check.name;
  }
}

TEST(LandmarkCheck, AFarLandmarkIsFlaggedNamedAndDownWeighted) {
  ToyScan c;
  auto named = c.landmarks();
  named[0].second += Vec3(0, 0, 80);  // the sternal notch clicked 80 mm too high (off the body)
  ScanTarget scan(c.mesh, 300);
  const FitResult robust = register_template(c.m, scan, match_landmarks(c.m, named), FitOptions{});
  const LandmarkCheck* moved = find(robust.summary, named[0].first);
  ASSERT_NE(moved, nullptr);
  EXPECT_TRUE(moved->flagged) << moved->distance_mm;
  EXPECT_LT(moved->factor, 1.0);
  bool warned = false;
  for (const auto& w : robust.summary.warnings) warned = warned || w.find("'" + named[0].first + "'") != std::string::npos;
  EXPECT_TRUE(warned);
  for (const auto& check : robust.summary.landmark_checks)
    if (check.name != named[0].first) EXPECT_FALSE(check.flagged) << check.name;

  // Without the robust stages the bad landmark drags the fit further from the true surface.
  FitOptions plain;
  for (StageOptions* s : plain.stages()) s->robust_landmarks = false;
  const FitResult dragged = register_template(c.m, scan, match_landmarks(c.m, named), plain);
  auto mean_distance = [&](const FitResult& r) {
    double sum = 0;
    for (Index i = 0; i < r.model_vertices.rows(); ++i) sum += (r.model_vertices.row(i) - c.mesh.V.row(i)).norm();
    return sum / r.model_vertices.rows();
  };
  EXPECT_LT(mean_distance(robust), mean_distance(dragged));
}

}  // namespace
}  // namespace breastfit::fit
