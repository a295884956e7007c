// The sternum's length from the notch and the nipples: the proportion itself, the xiphoid placed
// along the fitted sternum, its refusals, and the synthetic torsos' truth.
#include "breastfit/fit/sternum_length.h"

#include <gtest/gtest.h>

#include "fit/synth_anatomy.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;

TEST(SternumLength, TheProportionItself) {
  // Both nipples 250 mm from the notch: 0.314 × 250 + 136.5 = 215 mm.
  const Vec3 notch(10, 20, 30);
  const Vec3 right = notch + Vec3(-150, 0, -200), left = notch + Vec3(150, 0, -200);
  EXPECT_NEAR(sternum_length_by_nipples_mm(notch, right, left), 215.0, 1e-9);
  // The mean of the two distances: one nipple farther, the other nearer by as much.
  const Vec3 lower = notch + Vec3(150, 0, -200) * (260.0 / 250.0), higher = notch + Vec3(-150, 0, -200) * (240.0 / 250.0);
  EXPECT_NEAR(sternum_length_by_nipples_mm(notch, higher, lower), 215.0, 1e-9);
  SternumLengthOptions o;
  o.slope = 0.5;
  o.offset_mm = 100.0;
  EXPECT_NEAR(sternum_length_by_nipples_mm(notch, right, left, o), 225.0, 1e-9);
}

TEST(SternumLength, TheXiphoidKeepsTheFittedDirectionAndTakesTheLength) {
  const Vec3 notch = Vec3::Zero();
  const Vec3 right(-150, 0, -200), left(150, 0, -200);  // 215 mm
  const Vec3 dir = Vec3(0.1, 0.2, -1.0).normalized();
  for (const double fitted_length : {195.0, 215.0, 230.0}) {
    const auto x = xiphoid_by_nipples(notch, right, left, notch + fitted_length * dir);
    ASSERT_TRUE(x) << fitted_length;
    EXPECT_NEAR((*x - notch).norm(), 215.0, 1e-9);
    EXPECT_NEAR((*x - notch).normalized().dot(dir), 1.0, 1e-12);
  }
}

TEST(SternumLength, RefusedFarFromTheFittedXiphoidOrWithoutASternum) {
  const Vec3 notch = Vec3::Zero();
  const Vec3 right(-150, 0, -200), left(150, 0, -200);  // 215 mm
  EXPECT_FALSE(xiphoid_by_nipples(notch, right, left, Vec3(0, 0, -180)));  // 35 mm short
  EXPECT_TRUE(xiphoid_by_nipples(notch, right, left, Vec3(0, 0, -190)));   // 25 mm short
  EXPECT_FALSE(xiphoid_by_nipples(notch, right, left, notch));              // no direction
  SternumLengthOptions o;
  o.max_shift_mm = 20.0;
  EXPECT_FALSE(xiphoid_by_nipples(notch, right, left, Vec3(0, 0, -190), o));
}

// The template-made torsos (their proportions differ from the benchmark bodies'): the predicted
// length within 10 mm of the truth (−4 … +8 mm on 12 such torsos, seeds 1–12), and a fitted
// xiphoid 20 mm too high brought within that of the truth.
TEST(SternumLength, TheSyntheticTorsosTruth) {
  for (const auto pose : {synth::PoseType::Standing, synth::PoseType::Supine}) {
    const synth::SynthCase& c = synth_case(pose);
    const Vec3 notch = truth(c, "sternal_notch"), xiphoid = truth(c, "xiphoid");
    const double length = (xiphoid - notch).norm();
    EXPECT_NEAR(sternum_length_by_nipples_mm(notch, truth(c, "nipple_R"), truth(c, "nipple_L")), length, 10.0);
    const Vec3 high = xiphoid + 20.0 * body_frame(c).up;
    const auto placed = xiphoid_by_nipples(notch, truth(c, "nipple_R"), truth(c, "nipple_L"), high);
    ASSERT_TRUE(placed);
    EXPECT_LT((*placed - xiphoid).norm(), 10.0);
  }
}

}  // namespace
}  // namespace breastfit::fit
