// The lowest breast point under a hanging breast: when the slice at the fold's height meets the
// breast (and when not), the bottom of the lower pole found below it, and the refusals. Built on
// sagittal profiles made here: a chest wall and a breast in front of it.
#include "breastfit/fit/hanging_breast_fold.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "fit/unit_sternum_frame.h"

namespace breastfit::fit {
namespace {

// A 1 mm grid over laterals 90…110 and heights −350…−150: the chest wall at front −40 everywhere,
// and in front of it the breast's skin at `breast_front(height)` where that is finite.
Points torso(const std::function<double(double)>& breast_front) {
  std::vector<Vec3> pts;
  for (int l = 90; l <= 110; ++l)
    for (int h = -350; h <= -150; ++h) {
      pts.emplace_back(l, -40.0, h);
      const double f = breast_front(h);
      if (std::isfinite(f)) pts.emplace_back(l, f, h);
    }
  Points V(static_cast<Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i) V.row(static_cast<Index>(i)) = pts[i].transpose();
  return V;
}

const double kNone = std::numeric_limits<double>::quiet_NaN();

// A breast hanging down to −290: its front falls from the tip (front 36 at −250) to 10 at −290,
// the chest wall below.
double hanging(double h) {
  if (h > -200 || h < -290) return kNone;
  if (h >= -250) return 36.0 - (h + 250) * 0.3;
  return 36.0 - (-250 - h) * 0.65;  // 10 at −290
}

// A breast that meets the chest wall at −265, well above the fold's height (−285).
double receding(double h) {
  if (h > -200 || h < -265) return kNone;
  if (h >= -230) return 36.0;
  return 36.0 - (-230 - h) * 2.0;  // −34 at −265
}

// A breast hanging lower, to −292: in the slice at the fold's height (−285 ± 3) its front-most skin
// is 25 mm behind the tip — beyond the first margin (23 mm), within today's (28): such sides of
// generated torsos took the proportion's point on the breast's front.
double hanging_lower(double h) {
  if (h > -200 || h < -292) return kNone;
  if (h >= -250) return 36.0 - (h + 250) * 0.3;
  return 36.0 - (-250 - h) * (25.0 / 32.0);  // 11 at −282, 3.2 at −292
}

const Vec3 kTip(100, 36, -250);
const Vec3 kFitted(100, -30, -285);

TEST(HangingBreastFold, TheSliceAtTheFoldsHeightMeetsAHangingBreastOnly) {
  const SternumFrame f = test::unit_sternum_frame();
  // Hanging: the slice −288…−282's front-most skin is 15.2 (at −282), 20.8 behind the tip (< 28).
  EXPECT_TRUE(breast_hangs_over_fold(torso(hanging), kTip, kFitted, f, -285.0));
  // Receding: at −285 only the chest wall, 76 behind the tip.
  EXPECT_FALSE(breast_hangs_over_fold(torso(receding), kTip, kFitted, f, -285.0));
  // A stricter margin: the hanging breast's slice 22.75 mm behind is not enough.
  HangingBreastFoldOptions o;
  o.max_behind_tip_mm = 20.0;
  EXPECT_FALSE(breast_hangs_over_fold(torso(hanging), kTip, kFitted, f, -285.0, o));
  // No scan in the slice (the strip elsewhere across the body): not hanging.
  EXPECT_FALSE(breast_hangs_over_fold(torso(hanging), kTip, Vec3(300, -30, -285), f, -285.0));
}

TEST(HangingBreastFold, TheSliceAtTheFoldsHeightBehindTheTip) {
  const SternumFrame f = test::unit_sternum_frame();
  // The slice's front-most skin is its top row's (−282).
  EXPECT_NEAR(*fold_slice_behind_tip_mm(torso(hanging), kTip, kFitted, f, -285.0), 32.0 * 0.65, 1e-9);
  EXPECT_NEAR(*fold_slice_behind_tip_mm(torso(hanging_lower), kTip, kFitted, f, -285.0), 25.0, 1e-9);
  EXPECT_NEAR(*fold_slice_behind_tip_mm(torso(receding), kTip, kFitted, f, -285.0), 76.0, 1e-9);
  EXPECT_FALSE(fold_slice_behind_tip_mm(torso(hanging), kTip, Vec3(300, -30, -285), f, -285.0).has_value());
}

TEST(HangingBreastFold, TheLowestPointIfTheBreastHangs) {
  const SternumFrame f = test::unit_sternum_frame();
  // 25 mm behind the tip at the fold's height: it hangs, and its bottom is found (the last slice
  // with breast −291: its rows −292…−290, front-most 36 − 40 × 25/32; then the chest wall).
  const auto p = lowest_breast_if_hanging(torso(hanging_lower), kTip, kFitted, f, -285.0);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(p->z(), -291.0, 1e-9);
  EXPECT_NEAR(p->y(), 0.5 * ((36.0 - 40.0 * 25.0 / 32.0) + -40.0), 1e-9);
  // The same as the detector's own search where the breast hangs.
  EXPECT_EQ(*lowest_breast_if_hanging(torso(hanging), kTip, kFitted, f, -285.0),
            *hanging_breast_fold_on_scan(torso(hanging), kTip, kFitted, f, -285.0));
  // A breast receding above the fold's height: no point (the caller's proportions place it).
  EXPECT_FALSE(lowest_breast_if_hanging(torso(receding), kTip, kFitted, f, -285.0).has_value());
  // Hanging at the fold's height but no fall within reach below: no point either.
  HangingBreastFoldOptions o;
  o.max_below_mm = 2.0;
  EXPECT_FALSE(lowest_breast_if_hanging(torso(hanging_lower), kTip, kFitted, f, -285.0, o).has_value());
  // The first margin (23 mm) did not count the lower breast as hanging.
  o = HangingBreastFoldOptions{};
  o.max_behind_tip_mm = 23.0;
  EXPECT_FALSE(lowest_breast_if_hanging(torso(hanging_lower), kTip, kFitted, f, -285.0, o).has_value());
}

TEST(HangingBreastFold, TheBottomOfTheLowerPoleHalfwayToTheChestWall) {
  const SternumFrame f = test::unit_sternum_frame();
  const auto p = hanging_breast_fold_on_scan(torso(hanging), kTip, kFitted, f, -285.0);
  ASSERT_TRUE(p.has_value());
  // The last 3 mm slice with breast: −291 (within ±1.5 mm it holds the breast's bottom row at −290,
  // front 10); the next one (−294) holds the chest wall only.
  EXPECT_NEAR(p->z(), -291.0, 1e-9);
  EXPECT_NEAR(p->y(), 0.5 * (10.0 + -40.0), 1e-9);
  EXPECT_NEAR(p->x(), 100.0, 1e-9);  // the strip's middle: the fitted point's lateral position
}

TEST(HangingBreastFold, AHoleBelowTheBreastIsSkipped) {
  const SternumFrame f = test::unit_sternum_frame();
  Points V = torso(hanging);
  // No scan at all from −295 to −289 (the unseen underside and the chest wall just below).
  std::vector<Index> keep;
  for (Index i = 0; i < V.rows(); ++i)
    if (V(i, 2) > -289 || V(i, 2) < -295) keep.push_back(i);
  Points W(static_cast<Index>(keep.size()), 3);
  for (size_t k = 0; k < keep.size(); ++k) W.row(static_cast<Index>(k)) = V.row(keep[k]);
  const auto p = hanging_breast_fold_on_scan(W, kTip, kFitted, f, -285.0);
  ASSERT_TRUE(p.has_value());
  // The last slice with breast is −288 (its rows −288 and −287 left: front-most 36 − 37 × 0.65);
  // −291 and −294 are empty, the fall is found at −297.
  EXPECT_NEAR(p->z(), -288.0, 1e-9);
  EXPECT_NEAR(p->y(), 0.5 * ((36.0 - 37.0 * 0.65) + -40.0), 1e-9);
}

TEST(HangingBreastFold, RefusedWithoutAFallWithinReach) {
  const SternumFrame f = test::unit_sternum_frame();
  // The breast's front never falls by more than 20 mm from one slice to the next: a smooth descent.
  const auto smooth = [](double h) { return h > -200 ? kNone : 36.0 - (-200 - h) * 0.5; };
  EXPECT_FALSE(hanging_breast_fold_on_scan(torso(smooth), kTip, kFitted, f, -285.0).has_value());
  // The fall lies farther below the fold's height than allowed.
  HangingBreastFoldOptions o;
  o.max_below_mm = 2.0;
  EXPECT_FALSE(hanging_breast_fold_on_scan(torso(hanging), kTip, kFitted, f, -285.0, o).has_value());
  // A degenerate frame.
  SternumFrame bad = f;
  bad.length_mm = 0;
  EXPECT_FALSE(hanging_breast_fold_on_scan(torso(hanging), kTip, kFitted, bad, -285.0).has_value());
}

}  // namespace
}  // namespace breastfit::fit
