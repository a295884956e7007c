// The lowest breast point found on synthetic scans (standing and supine) from the breast's tip,
// starting from a fitted point as far off as the fit leaves it without the landmark; and placed by
// the sternum's and the nipple's proportions.
#include "breastfit/fit/breast_fold.h"

#include <gtest/gtest.h>

#include <cmath>
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

// The sternum's frame of the case's truth on one side.
SternumFrame truth_sternum(const synth::SynthCase& c, char side) {
  const auto frame = sternum_frame(truth(c, "sternal_notch"), truth(c, "xiphoid"), truth(c, "nipple_R"),
                                   truth(c, "nipple_L"), side);
  EXPECT_TRUE(frame);
  return frame.value_or(SternumFrame{});
}

TEST(BreastFoldProportion, TheHeightAveragesTheSternumsAndTheNipplesPredictions) {
  SternumFrame frame;
  frame.length_mm = 200.0;
  BreastFoldProportionOptions o;
  o.sternum_drop = 1.25;
  o.nipple_slope = 0.5;
  o.nipple_offset_mm = 150.0;
  o.nipple_share = 0.0;
  EXPECT_DOUBLE_EQ(lowest_breast_drop_mm(frame, 180.0, o), 250.0);
  o.nipple_share = 1.0;
  EXPECT_DOUBLE_EQ(lowest_breast_drop_mm(frame, 180.0, o), 240.0);
  o.nipple_share = 0.5;
  EXPECT_DOUBLE_EQ(lowest_breast_drop_mm(frame, 180.0, o), 245.0);
  // A lower nipple (a hanging breast): a lower fold.
  EXPECT_GT(lowest_breast_drop_mm(frame, 200.0, o), lowest_breast_drop_mm(frame, 180.0, o));
}

// At the truth's height (from a fitted point 35 mm too high and 10 mm to the side) the point found
// is the skin's front there: no scan of the slice and strip lies in front of it. On the supine
// torso that is the lowest breast point; on the standing one, made from the template, the breast
// hangs in front of the template's fold (the benchmark's truths lie on the skin's front).
void expect_front_at_the_truths_height(synth::PoseType pose, bool at_truth) {
  const synth::SynthCase& c = synth_case(pose);
  for (const char side : {'R', 'L'}) {
    const std::string s(1, side);
    const SternumFrame frame = truth_sternum(c, side);
    const Vec3 lowest = truth(c, "lowest_breast_" + s), tip = truth(c, "nipple_" + s);
    BreastFoldProportionOptions o;
    o.nipple_share = 0.0;
    o.sternum_drop = -sternum_coordinates(frame, lowest).height / frame.length_mm;
    const Vec3 fitted = lowest + 35.0 * frame.up + 10.0 * frame.lateral;
    const auto found = lowest_breast_by_proportion(c.scan.V, tip, fitted, frame, o);
    ASSERT_TRUE(found) << synth::pose_type_name(pose) << " " << side;
    const SternumCoordinates f = sternum_coordinates(frame, *found), fit = sternum_coordinates(frame, fitted);
    EXPECT_NEAR(f.height, sternum_coordinates(frame, lowest).height, o.height_half_window_mm + 1e-9);
    EXPECT_NEAR(f.lateral, fit.lateral, o.strip_half_width_mm + 1e-9);
    const double height = sternum_coordinates(frame, lowest).height;
    const double front_limit = sternum_coordinates(frame, tip).front + o.max_in_front_of_tip_mm;
    for (Index i = 0; i < c.scan.V.rows(); ++i) {
      const SternumCoordinates p = sternum_coordinates(frame, c.scan.V.row(i).transpose());
      if (std::abs(p.height - height) < o.height_half_window_mm && std::abs(p.lateral - fit.lateral) < o.strip_half_width_mm &&
          p.front < front_limit)
        EXPECT_LE(p.front, f.front);
    }
    if (at_truth)
      EXPECT_LT((*found - lowest).norm(), 15.0) << synth::pose_type_name(pose) << " " << side << ": "
                                                << found->transpose() << " vs " << lowest.transpose();
  }
}

TEST(BreastFoldProportion, FindsTheSkinsFrontAtTheHeightOnAStandingScan) {
  expect_front_at_the_truths_height(synth::PoseType::Standing, false);
}

TEST(BreastFoldProportion, FindsTheLowestBreastPointAtTheHeightOnASupineScan) {
  expect_front_at_the_truths_height(synth::PoseType::Supine, true);
}

TEST(BreastFoldProportion, RefusesWhenUnsure) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const SternumFrame frame = truth_sternum(c, 'R');
  const Vec3 tip = truth(c, "nipple_R");
  const Vec3 fitted = truth(c, "lowest_breast_R") + 35.0 * frame.up;
  ASSERT_TRUE(lowest_breast_by_proportion(c.scan.V, tip, fitted, frame));
  // No scan, no sternum.
  EXPECT_FALSE(lowest_breast_by_proportion(Points(0, 3), tip, fitted, frame));
  EXPECT_FALSE(lowest_breast_by_proportion(c.scan.V, tip, fitted, SternumFrame{}));
  // A tip far behind the body: nothing at that height lies behind it.
  EXPECT_FALSE(lowest_breast_by_proportion(c.scan.V, tip - 400.0 * frame.front, fitted, frame));
  // The point farther from the fitted one than allowed.
  BreastFoldProportionOptions strict;
  strict.max_shift_mm = 5.0;
  EXPECT_FALSE(lowest_breast_by_proportion(c.scan.V, tip, fitted, frame, strict));
  // A strip beside the body (the fitted point 300 mm to the side): empty.
  EXPECT_FALSE(lowest_breast_by_proportion(c.scan.V, tip, fitted + 300.0 * frame.lateral, frame));
}

}  // namespace
}  // namespace breastfit::fit
