// The combined check: the anatomical tolerance lowered by how far the prediction moved, so two
// checks each below their tolerance flag together; the xiphoid is not checked this way.
#include "breastfit/fit/combined_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace breastfit::fit {
namespace {

TEST(CombinedCheck, EveryLandmarkWithAnAnatomicalCheckButTheXiphoid) {
  for (const char* name : {"sternal_notch", "acromion_R", "acromion_L", "midaxillary_R", "midaxillary_L",
                           "pectoral_insertion_R", "pectoral_insertion_L", "nipple_R", "nipple_L",
                           "lowest_breast_R", "lowest_breast_L"}) {
    const auto t = combined_check_threshold(name);
    ASSERT_TRUE(t) << name;
    // Above either check's own limit alone would be pointless (1 = each check's own tolerance),
    // and so would be below the landmarks as given (at most 0.9 of it, combined_check.h).
    EXPECT_GT(*t, 0.5) << name;
    EXPECT_LE(*t, 1.0) << name;
  }
  EXPECT_FALSE(combined_check_threshold("xiphoid"));
  EXPECT_FALSE(combined_anatomy_tolerance_mm("xiphoid", 0.5, 18.0));
}

TEST(CombinedCheck, ThePredictionLowersTheAnatomicalTolerance) {
  // The nipple: threshold 0.85. Prediction on the spot: the tip's 18 mm become 18·√0.85.
  EXPECT_NEAR(*combined_anatomy_tolerance_mm("nipple_R", 0.0, 18.0), 18.0 * std::sqrt(0.85), 1e-9);
  // Both at 0.7 of their tolerances: 0.49 + 0.49 > 0.85, flagged (12.6 mm > the lowered tolerance).
  const double lowered = *combined_anatomy_tolerance_mm("nipple_R", 0.7, 18.0);
  EXPECT_LT(lowered, 0.7 * 18.0);
  // The anatomy at 0.7 alone is within (0.49 < 0.85).
  EXPECT_GT(*combined_anatomy_tolerance_mm("nipple_R", 0.0, 18.0), 0.7 * 18.0);
  // Monotone in the prediction's ratio, never negative.
  double last = 1e9;
  for (double r = 0; r <= 1.5; r += 0.1) {
    const double t = *combined_anatomy_tolerance_mm("pectoral_insertion_L", r, 20.0);
    EXPECT_LE(t, last);
    EXPECT_GE(t, 0.0);
    last = t;
  }
}

}  // namespace
}  // namespace breastfit::fit
