// The acromion of a hanging arm: the refined model's point moved up and towards the midline in the
// sternum's frame of its side, on both sides and in a turned frame.
#include "breastfit/fit/hanging_acromion.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace breastfit::fit {
namespace {

TEST(HangingAcromion, UpAndTowardsTheMidlineOnEitherSide) {
  const Vec3 notch(0, 0, 0), xiphoid(0, 0, -200), right(-100, 30, -180), left(100, 30, -180);
  const auto fr = sternum_frame(notch, xiphoid, right, left, 'R');
  const auto fl = sternum_frame(notch, xiphoid, right, left, 'L');
  ASSERT_TRUE(fr && fl);
  // Right side: lateral is −x, so medial is +x.
  const Vec3 r = hanging_acromion_target(Vec3(-180, -20, 10), *fr);
  EXPECT_NEAR((r - Vec3(-180 + 4.3, -20, 10 + 4.5)).norm(), 0.0, 1e-9);
  const Vec3 l = hanging_acromion_target(Vec3(180, -20, 10), *fl);
  EXPECT_NEAR((l - Vec3(180 - 4.3, -20, 10 + 4.5)).norm(), 0.0, 1e-9);
  HangingAcromionOptions o;
  o.up_mm = 0;
  o.medial_mm = 0;
  EXPECT_NEAR((hanging_acromion_target(Vec3(1, 2, 3), *fl, o) - Vec3(1, 2, 3)).norm(), 0.0, 1e-12);
}

TEST(HangingAcromion, MovesWithTheBodyNotTheScannersAxes) {
  // The same torso turned 90° about the scanner's x axis and moved: the target turns and moves with it.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Vec3::UnitX()).toRotationMatrix();
  const Vec3 t(500, -200, 1000);
  const auto at = [&](const Vec3& p) -> Vec3 { return R * p + t; };
  const Vec3 notch(0, 0, 0), xiphoid(0, 0, -200), right(-100, 30, -180), left(100, 30, -180), fitted(180, -20, 10);
  const auto f = sternum_frame(notch, xiphoid, right, left, 'L');
  const auto g = sternum_frame(at(notch), at(xiphoid), at(right), at(left), 'L');
  ASSERT_TRUE(f && g);
  EXPECT_NEAR((hanging_acromion_target(at(fitted), *g) - at(hanging_acromion_target(fitted, *f))).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace breastfit::fit
