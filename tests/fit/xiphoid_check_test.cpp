// The xiphoid against the lowest breast points' height: the synthetic torsos' truth is within,
// a xiphoid moved 20 mm down the abdomen is not.
#include "breastfit/fit/xiphoid_check.h"

#include <gtest/gtest.h>

#include "fit/synth_anatomy.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;

double residual(const synth::SynthCase& c, const Vec3& xiphoid) {
  return xiphoid_residual_mm(truth(c, "sternal_notch"), xiphoid, truth(c, "lowest_breast_R"),
                             truth(c, "lowest_breast_L"), body_frame(c).up);
}

TEST(XiphoidCheck, TruthIsWithinAndAXiphoidMovedDownIsNot) {
  for (const auto pose : {synth::PoseType::Standing, synth::PoseType::Supine}) {
    const synth::SynthCase& c = synth_case(pose);
    const Vec3 x = truth(c, "xiphoid");
    const double r = residual(c, x);
    EXPECT_LT(r, kXiphoidTooLowMm) << "truth";
    const Vec3 down = -body_frame(c).up;
    EXPECT_NEAR(residual(c, x + 20.0 * down) - r, 20.0, 1e-6);
    EXPECT_GT(residual(c, x + 20.0 * down), kXiphoidTooLowMm);
    // Sideways does not change the sternum's length along its axis.
    EXPECT_NEAR(residual(c, x + 20.0 * body_frame(c).front.cross(body_frame(c).up)), r, 1e-6);
  }
}

TEST(XiphoidCheck, TheProportionItself) {
  // Notch at the origin, lowest breast points 1.277 × 200 mm below: a 200 mm sternum fits exactly.
  const Vec3 up = Vec3::UnitZ();
  const Vec3 lb(0, 0, -kLowestBreastSternumLengths * 200.0);
  EXPECT_NEAR(xiphoid_residual_mm(Vec3::Zero(), Vec3(0, 0, -200.0), lb, lb, up), 0.0, 1e-9);
  EXPECT_NEAR(xiphoid_residual_mm(Vec3::Zero(), Vec3(0, 0, -215.0), lb, lb, up), 15.0, 1e-9);
}

}  // namespace
}  // namespace breastfit::fit
