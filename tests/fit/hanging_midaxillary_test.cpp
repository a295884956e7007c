// The mid-axillary point of a hanging arm's side: the strip's place (height by the sternum's
// proportion, in front of the fitted point), the vertex closest across the body, the refusals, and
// the synthetic standing torso from a fitted point left behind the truth.
#include "breastfit/fit/hanging_midaxillary.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fit/synth_anatomy.h"
#include "fit/unit_sternum_frame.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;

// A side wall at `lateral` mm: a 1 mm grid over heights −200…−100 and fronts −120…−40.
Points wall(double lateral) {
  Points V(101 * 81, 3);
  Index k = 0;
  for (int h = 0; h <= 100; ++h)
    for (int f = 0; f <= 80; ++f) V.row(k++) = Vec3(lateral, -40.0 - f, -100.0 - h).transpose();
  return V;
}

TEST(HangingMidaxillary, TheStripInFrontOfTheFittedPointAtTheProportionsHeight) {
  const SternumFrame f = test::unit_sternum_frame();
  Points V = wall(150.0);
  V.row(0) = Vec3(146.0, -83.0, -144.0).transpose();  // nearer across the body, inside the strip
  const Vec3 fitted(145.0, -90.0, -135.0);
  const auto p = hanging_midaxillary_on_scan(V, fitted, f);
  ASSERT_TRUE(p);
  EXPECT_TRUE(p->isApprox(Vec3(146.0, -83.0, -144.0)));
  const SternumCoordinates c = sternum_coordinates(f, *p);
  EXPECT_LE(std::abs(c.height + 0.721 * 200.0), 4.0);
  EXPECT_LE(std::abs(c.front - (-90.0 + 7.0)), 4.0);
}

TEST(HangingMidaxillary, RefusedWithoutScanInTheStripOrFarFromTheFittedPoint) {
  const SternumFrame f = test::unit_sternum_frame();
  // The wall 40 mm beyond the fitted point across the body (an arm met instead of the chest).
  EXPECT_FALSE(hanging_midaxillary_on_scan(wall(190.0), Vec3(150.0, -90.0, -144.0), f));
  EXPECT_TRUE(hanging_midaxillary_on_scan(wall(155.0), Vec3(150.0, -90.0, -144.0), f));  // any of the strip < 15 mm
  // The strip 7 mm in front of a fitted point at the wall's front edge holds nothing.
  EXPECT_FALSE(hanging_midaxillary_on_scan(wall(150.0), Vec3(150.0, -25.0, -144.0), f));
  SternumFrame none = f;
  none.length_mm = 0.0;
  EXPECT_FALSE(hanging_midaxillary_on_scan(wall(150.0), Vec3(150.0, -90.0, -144.0), none));
}

// The template-made standing torso: a fitted point 8 mm behind the truth along the skin gives a
// point on the chest wall nearer the truth.
TEST(HangingMidaxillary, TheSyntheticStandingTorsoFromAPointLeftBehind) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Points& S = c.scan.V;
  for (const char side : {'R', 'L'}) {
    const auto frame = fit::sternum_frame(truth(c, "sternal_notch"), truth(c, "xiphoid"), truth(c, "nipple_R"),
                                          truth(c, "nipple_L"), side);
    ASSERT_TRUE(frame);
    const Vec3 t = truth(c, std::string("midaxillary_") + side);
    const Vec3 behind = t - 8.0 * frame->front;
    const auto p = hanging_midaxillary_on_scan(S, behind, *frame);
    ASSERT_TRUE(p) << side;
    EXPECT_LT((*p - t).norm(), (behind - t).norm()) << side;
  }
}

}  // namespace
}  // namespace breastfit::fit
