// A nipple against the bump found on the scan: beyond 12 mm (scaled with landmark_check_mm) it is
// flagged.
#include "breastfit/fit/nipple_bump_check.h"

#include <gtest/gtest.h>

namespace breastfit::fit {
namespace {

NippleBump bump_at(const Vec3& p) {
  NippleBump b;
  b.position = p;
  b.peak_mm = 5.0;
  b.median_mm = 1.5;
  b.second_mm = 3.0;
  return b;
}

TEST(NippleBumpCheck, WithinTheToleranceIsNotFlagged) {
  const NippleBump b = bump_at(Vec3(100, 50, -150));
  const NippleBumpCheck c = check_nipple_bump(Vec3(100, 60, -150), b, 15.0);
  EXPECT_NEAR(c.distance_mm, 10.0, 1e-9);
  EXPECT_NEAR(c.tolerance_mm, kNippleBumpCheckMm, 1e-9);
  EXPECT_FALSE(c.flagged());
}

TEST(NippleBumpCheck, AWalkedNippleIsFlagged) {
  const NippleBump b = bump_at(Vec3(100, 50, -150));
  EXPECT_TRUE(check_nipple_bump(Vec3(100, 50, -130), b, 15.0).flagged());
  EXPECT_TRUE(check_nipple_bump(Vec3(100, 63, -150), b, 15.0).flagged());
}

TEST(NippleBumpCheck, ToleranceScalesWithTheLandmarkCheck) {
  const NippleBump b = bump_at(Vec3::Zero());
  EXPECT_NEAR(check_nipple_bump(Vec3::Zero(), b, 30.0).tolerance_mm, 2 * kNippleBumpCheckMm, 1e-9);
  EXPECT_FALSE(check_nipple_bump(Vec3(20, 0, 0), b, 30.0).flagged());
}

}  // namespace
}  // namespace breastfit::fit
