// A nipple against the breast's apex: above it or behind it (with the tip check agreeing) is
// flagged; a template-like nipple below and behind the apex is not.
#include "breastfit/fit/nipple_apex_check.h"

#include <gtest/gtest.h>

namespace breastfit::fit {
namespace {

SternumFrame frame() {
  SternumFrame f;
  f.up = Vec3::UnitZ();
  f.front = Vec3::UnitY();
  f.lateral = Vec3::UnitX();
  return f;
}

const Vec3 kApex(100.0, 50.0, -150.0);

NippleApexCheck at(double side, double up, double front, double tip_ratio) {
  return check_nipple_apex(frame(), kApex + Vec3(side, front, up), kApex, tip_ratio);
}

TEST(NippleApexCheck, OnTheApexOrAsGivenIsWithin) {
  EXPECT_FALSE(at(0, 0, 0, 0.9).flagged());
  // The spread of the nipples as given on the benchmark torsos: up to 8.8 mm above, 7.3 mm
  // sideways, 1.7 mm behind.
  EXPECT_FALSE(at(7.3, 8.8, -1.7, 0.74).flagged());
  EXPECT_FALSE(at(-7.3, -2.6, 1.7, 0.74).flagged());
}

TEST(NippleApexCheck, AboveTheApexIsFlagged) {
  const NippleApexCheck c = at(0, 14.0, 0, 0.0);
  EXPECT_TRUE(c.flagged());
  EXPECT_NEAR(c.deviation.y(), 14.0, 1e-9);
  EXPECT_NEAR(c.tolerance_mm, kApexAboveMm, 1e-9);  // along the vertical, the rule's boundary
  EXPECT_FALSE(at(0, 11.0, 0, 0.0).flagged());
}

TEST(NippleApexCheck, BehindTheApexNeedsTheTipToAgree) {
  EXPECT_TRUE(at(3.0, -3.0, -8.0, 0.7).flagged());
  EXPECT_FALSE(at(3.0, -3.0, -8.0, 0.5).flagged());  // the tip check close: one signal only
  EXPECT_FALSE(at(3.0, 0.0, -4.0, 0.9).flagged());   // within 5 mm behind
}

TEST(NippleApexCheck, TheTemplatesNippleBelowTheApexIsNotFlagged) {
  // The template-made torsos' nipple: ~20 mm below the level apex and up to 17 mm behind it.
  EXPECT_FALSE(at(5.0, -20.0, -12.0, 0.9).flagged());
  EXPECT_FALSE(at(0.0, -30.0, -17.0, 0.9).flagged());
}

}  // namespace
}  // namespace breastfit::fit
