#include "breastfit/fit/landmark_target.h"

#include <gtest/gtest.h>

namespace breastfit::fit {
namespace {

TEST(LandmarkTarget, FindLandmarkGivesTheFirstOfThatNameOrNothing) {
  const std::vector<LandmarkTarget> targets = {{"nipple_R", 3, Vec3(1, 0, 0), 1.0},
                                               {"sternal_notch", 0, Vec3(2, 0, 0), 1.0},
                                               {"nipple_R", 3, Vec3(9, 0, 0), 0.5}};
  const LandmarkTarget* notch = find_landmark(targets, "sternal_notch");
  ASSERT_NE(notch, nullptr);
  EXPECT_EQ(notch, &targets[1]);
  const LandmarkTarget* nipple = find_landmark(targets, "nipple_R");
  ASSERT_NE(nipple, nullptr);
  EXPECT_EQ(nipple, &targets[0]);
  EXPECT_EQ(find_landmark(targets, "nipple_L"), nullptr);
  EXPECT_EQ(find_landmark({}, "nipple_R"), nullptr);
}

}  // namespace
}  // namespace breastfit::fit
