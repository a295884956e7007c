#include "breastfit/fit/landmark_check.h"

#include <gtest/gtest.h>

#include "breastfit/fit/registration.h"
#include "breastfit/mesh/normals.h"
#include "support/test_shapes.h"
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

TEST(LandmarkCheck, FindsTheBreastTipOnTheScanNearTheFittedNipple) {
  // The fitted model: a sphere (radius 60 mm) with its nipple at the front, (0, −60, 0), facing −y.
  // The scan: the same sphere moved by (15, −20, 0): its tip along −y is (15, −80, 0).
  const TriangleMesh model = test::sphere_mesh(60.0, Vec3::Zero(), 64, 128);
  const TriangleMesh scan = test::sphere_mesh(60.0, Vec3(15, -20, 0), 64, 128);
  const Points N = mesh::vertex_normals(model);
  const auto tip = breast_tip_on_scan(scan.V, model.V, N, Vec3(0, -60, 0));
  ASSERT_TRUE(tip);
  EXPECT_LT((*tip - Vec3(15, -80, 0)).norm(), 3.0) << tip->transpose();
  // No scan near the nipple: nothing found.
  EXPECT_FALSE(breast_tip_on_scan(scan.V, model.V, N, Vec3(0, -500, 0)));
}

TEST(LandmarkCheck, ExchangedLabelsAreThePairsThatBelongAtEachOther) {
  auto at = [](const std::string& name, const Vec3& p) { return LandmarkTarget{name, 0, p, landmark_weight(name)}; };
  // Where the anatomy and the other landmarks put them.
  const std::vector<Vec3> predicted = {Vec3(0, 0, 0), Vec3(0, 0, -120), Vec3(90, 0, -140), Vec3(90, 0, -200)};
  // nipple_L and lowest_breast_L clicked with each other's label; the others as predicted.
  const std::vector<LandmarkTarget> given = {at("sternal_notch", Vec3(1, 0, 0)), at("xiphoid", Vec3(0, 2, -120)),
                                             at("nipple_L", Vec3(90, 0, -201)), at("lowest_breast_L", Vec3(91, 0, -140))};
  const auto pairs = exchanged_labels(given, predicted, 15.0);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(size_t{2}, size_t{3}));
  // One landmark off alone is not an exchange.
  auto one_off = given;
  one_off[3].position = Vec3(91, 0, -200);
  one_off[2].position = Vec3(140, 0, -140);
  EXPECT_TRUE(exchanged_labels(one_off, predicted, 15.0).empty());
  // The landmarks as predicted: nothing.
  auto fine = given;
  fine[2].position = predicted[2];
  fine[3].position = predicted[3];
  EXPECT_TRUE(exchanged_labels(fine, predicted, 15.0).empty());
}

// The toy model's "breasts" are small bumps that random poses can turn into dents: no tip to
// check its nipples against, so these tests switch the breast-tip check off.
FitOptions toy_options() {
  FitOptions o;
  o.nipple_tip_check_mm = 1e3;
  return o;
}

struct ToyScan : test::ToyScanCase {
  ToyScan() : ToyScanCase(31, 0.4) {}
  std::vector<std::pair<std::string, Vec3>> landmarks() const { return named_landmarks(); }
};

const LandmarkCheck* find(const FitSummary& s, const std::string& name) {
  for (const auto& c : s.landmark_checks)
    if (c.name == name) return &c;
  return nullptr;
}

TEST(LandmarkCheck, LandmarksAsPlacedAreNotFlagged) {
  ToyScan c;
  ScanTarget scan(c.mesh, 300);
  const FitResult r = register_template(c.m, scan, match_landmarks(c.m, c.landmarks()), toy_options());
  ASSERT_EQ(r.summary.landmark_checks.size(), c.m.landmarks.size());
  for (const auto& check : r.summary.landmark_checks) {
    EXPECT_FALSE(check.flagged) << check.name << " " << check.distance_mm << " tip " << check.anatomy_distance_mm;
    EXPECT_EQ(check.factor, 1.0) << check.name;
  }
}

TEST(LandmarkCheck, AFarLandmarkIsFlaggedNamedAndDownWeighted) {
  ToyScan c;
  auto named = c.landmarks();
  named[0].second += Vec3(0, 0, 80);  // the sternal notch clicked 80 mm too high (off the body)
  ScanTarget scan(c.mesh, 300);
  const FitResult robust = register_template(c.m, scan, match_landmarks(c.m, named), toy_options());
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
  FitOptions plain = toy_options();
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
