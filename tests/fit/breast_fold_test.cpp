// The lowest breast point found on synthetic scans (standing and supine) from the breast's tip,
// starting from a fitted point as far off as the fit leaves it without the landmark.
#include "breastfit/fit/breast_fold.h"

#include <gtest/gtest.h>

#include <string>

#include "fit/synth_anatomy.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;  // the synthetic torsos, their truth and body frame

void expect_fold_found(synth::PoseType pose) {
  const synth::SynthCase& c = synth_case(pose);
  const Frame f = body_frame(c);
  for (const char* side : {"R", "L"}) {
    const Vec3 lowest = truth(c, std::string("lowest_breast_") + side);
    const Vec3 tip = truth(c, std::string("nipple_") + side);
    // The fitted lower pole without the landmark: about 35 mm too high.
    const Vec3 fitted = lowest + 35.0 * f.up;
    const auto fold = lowest_breast_on_scan(c.scan.V, tip, fitted, f.up, f.front);
    ASSERT_TRUE(fold) << synth::pose_type_name(pose) << " " << side;
    EXPECT_LT((*fold - lowest).norm(), 20.0) << synth::pose_type_name(pose) << " " << side << ": "
                                             << fold->transpose() << " vs " << lowest.transpose();
    EXPECT_LT((*fold - lowest).norm(), (fitted - lowest).norm());
  }
}

TEST(BreastFold, FindsTheLowestBreastPointOnAStandingScan) { expect_fold_found(synth::PoseType::Standing); }

TEST(BreastFold, FindsTheLowestBreastPointOnASupineScan) { expect_fold_found(synth::PoseType::Supine); }

TEST(BreastFold, RefusesWhenUnsure) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  const Vec3 tip = truth(c, "nipple_R");
  const Vec3 fitted = truth(c, "lowest_breast_R") + 35.0 * f.up;
  // A band missing below the tip (40 mm high, all round): the profile has a hole.
  Points holed(c.scan.V.rows(), 3);
  Index n = 0;
  for (Index i = 0; i < c.scan.V.rows(); ++i) {
    const Vec3 d = c.scan.V.row(i).transpose() - tip;
    const double drop = -d.dot(f.up);
    if (drop > 15 && drop < 55) continue;
    holed.row(n++) = c.scan.V.row(i);
  }
  holed.conservativeResize(n, 3);
  EXPECT_FALSE(lowest_breast_on_scan(holed, tip, fitted, f.up, f.front));
  // A tip that is not in front of the body (the skin below never recedes that far): no fold.
  EXPECT_FALSE(lowest_breast_on_scan(c.scan.V, tip - 80.0 * f.front, fitted, f.up, f.front));
  // No scan at all.
  EXPECT_FALSE(lowest_breast_on_scan(Points(0, 3), tip, fitted, f.up, f.front));
  // The crossing far below the fitted lower pole (a breast shallower than the fold's depth):
  // refused once the fitted point lies more than max_below_fitted_mm above it.
  const auto fold = lowest_breast_on_scan(c.scan.V, tip, fitted, f.up, f.front);
  ASSERT_TRUE(fold);
  const double below = (fitted - *fold).dot(f.up);
  BreastFoldOptions strict;
  strict.max_below_fitted_mm = below - 1.0;
  EXPECT_FALSE(lowest_breast_on_scan(c.scan.V, tip, fitted, f.up, f.front, strict));
  strict.max_below_fitted_mm = below + 1.0;
  EXPECT_TRUE(lowest_breast_on_scan(c.scan.V, tip, fitted, f.up, f.front, strict));
}

}  // namespace
}  // namespace breastfit::fit
