// A bilateral landmark checked against its partner mirrored across the other landmarks' midline:
// on the synthetic torsos' truth landmarks (no pair off), one landmark moved along each axis
// (its pair off, along that axis, and it blamed), and one wrong landmark of another pair (the midline holds).
#include "breastfit/fit/bilateral_check.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "fit/synth_anatomy.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;  // the synthetic torsos, their truth and body frame

void move(std::vector<LandmarkTarget>& landmarks, const std::string& name, const Vec3& by) {
  for (auto& t : landmarks)
    if (t.name == name) t.position += by;
}

const BilateralCheck* pair_of(const std::vector<BilateralCheck>& checks, const std::string& right) {
  for (const auto& c : checks)
    if (c.right == right) return &c;
  return nullptr;
}

TEST(BilateralCheck, TruthLandmarksAreSymmetricWithinTolerance) {
  for (const auto pose : {synth::PoseType::Standing, synth::PoseType::Supine}) {
    const auto checks = check_bilateral_pairs(truth_targets(synth_case(pose)), 15.0);
    ASSERT_EQ(checks.size(), 3u);  // acromia, mid-axillary points, lowest breast points
    for (const auto& c : checks) {
      EXPECT_FALSE(c.flagged()) << c.right << ": " << c.distance_mm << " mm, tolerance " << c.tolerance_mm;
      EXPECT_EQ(c.left.substr(0, c.left.size() - 1), c.right.substr(0, c.right.size() - 1));
    }
  }
}

// Each move takes the landmark away from the typical proportions on this template-made torso: a
// move towards them can be blamed on the partner (bilateral_check.h).
TEST(BilateralCheck, MovedLandmarkPutsItsPairOffAlongTheMove) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  const Vec3 side = f.up.cross(f.front);
  const struct {
    std::string name;
    Vec3 by;
    std::string axis;
  } moves[] = {{"acromion_R", 25.0 * f.up, "vertically"},
               {"lowest_breast_R", 20.0 * f.up, "vertically"},
               {"midaxillary_R", 20.0 * f.front, "front to back"},
               {"acromion_L", -30.0 * side, "sideways"}};
  for (const auto& m : moves) {
    auto landmarks = truth_targets(c);
    move(landmarks, m.name, m.by);
    const auto checks = check_bilateral_pairs(landmarks, 15.0);
    const std::string right = m.name.substr(0, m.name.size() - 1) + "R";
    const BilateralCheck* off = pair_of(checks, right);
    ASSERT_NE(off, nullptr) << m.name;
    EXPECT_TRUE(off->flagged()) << m.name << ": " << off->distance_mm << " mm, tolerance " << off->tolerance_mm;
    EXPECT_EQ(off->axis, m.axis) << m.name;
    EXPECT_EQ(off->blamed, m.name);  // moved away from the typical proportions, its partner not
    for (const auto& other : checks)
      if (other.right != right) EXPECT_FALSE(other.flagged()) << m.name << " moved, " << other.right << " flagged";
    // Scaled with landmark_check_mm: a huge one turns the check off.
    for (const auto& other : check_bilateral_pairs(landmarks, 1e6)) EXPECT_FALSE(other.flagged());
  }
}

TEST(BilateralCheck, OneWrongLandmarkDoesNotTiltTheMidline) {
  // A nipple clicked 40 mm off sideways tilts a mean right → left direction; the median holds.
  const synth::SynthCase& c = synth_case(synth::PoseType::Supine);
  const Frame f = body_frame(c);
  auto landmarks = truth_targets(c);
  move(landmarks, "nipple_L", 40.0 * f.up.cross(f.front) + 20.0 * f.up);
  for (const auto& check : check_bilateral_pairs(landmarks, 15.0))
    EXPECT_FALSE(check.flagged()) << check.right << ": " << check.distance_mm << " mm";
}

// The combined check also weighs the member not blamed, but only while the pair is within its
// tolerance: beyond it the blamed one is flagged and its partner left alone.
TEST(BilateralCheck, TheMemberNotBlamedIsLeftToTheCombinedCheckWithinTheTolerance) {
  BilateralCheck within;
  within.right = "lowest_breast_R";
  within.left = "lowest_breast_L";
  within.blamed = "lowest_breast_L";
  within.distance_mm = 9.0;
  within.tolerance_mm = 10.0;
  ASSERT_TRUE(unblamed_member(within).has_value());
  EXPECT_EQ(*unblamed_member(within), "lowest_breast_R");
  within.blamed = "lowest_breast_R";
  EXPECT_EQ(*unblamed_member(within), "lowest_breast_L");
  BilateralCheck beyond = within;
  beyond.distance_mm = 11.0;
  EXPECT_FALSE(unblamed_member(beyond).has_value());
  // On a torso: a lowest breast point moved 8 mm up leaves the pair within, both members weighed.
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  auto landmarks = truth_targets(c);
  move(landmarks, "lowest_breast_R", 8.0 * f.up);
  bool seen = false;
  for (const auto& check : check_bilateral_pairs(landmarks, 15.0))
    if (check.right == "lowest_breast_R") {
      seen = true;
      EXPECT_FALSE(check.flagged()) << check.distance_mm << " mm";
      ASSERT_TRUE(unblamed_member(check).has_value());
      EXPECT_NE(*unblamed_member(check), check.blamed);
    }
  EXPECT_TRUE(seen);
}

// The acromia 30 mm from mirror images, tolerance 18 mm, acromion_L blamed by the proportions.
BilateralCheck acromia_beyond_tolerance() {
  BilateralCheck c;
  c.right = "acromion_R";
  c.left = "acromion_L";
  c.distance_mm = 30.0;
  c.tolerance_mm = 18.0;
  c.blamed = "acromion_L";
  return c;
}

// Session 18: a pair beyond its tolerance blames the member whose prediction moved (3× its
// partner's, at least 0.4 of its tolerance) over the proportions' guess; acromia and mid-axillary
// points only, and only beyond the tolerance.
TEST(BilateralCheck, APairBeyondItsToleranceBlamesTheMemberWhosePredictionMoved) {
  BilateralCheck c = acromia_beyond_tolerance();  // acromion_L blamed by proportions
  EXPECT_EQ(blamed_by_prediction(c, 0.6, 0.1), "acromion_R");
  EXPECT_EQ(blamed_by_prediction(c, 0.6, 0.25), "acromion_L");   // 2.4×: the proportions' blame stands
  EXPECT_EQ(blamed_by_prediction(c, 0.35, 0.05), "acromion_L");  // below 0.4 of its tolerance
  EXPECT_EQ(blamed_by_prediction(c, 0.1, 0.6), "acromion_L");
  c.blamed = "acromion_R";
  EXPECT_EQ(blamed_by_prediction(c, 0.1, 0.6), "acromion_L");
  c.right = "midaxillary_R";
  c.left = "midaxillary_L";
  c.blamed = "midaxillary_L";
  EXPECT_EQ(blamed_by_prediction(c, 0.7, 0.1), "midaxillary_R");
  c.right = "lowest_breast_R";  // their prediction does not tell the two apart
  c.left = "lowest_breast_L";
  c.blamed = "lowest_breast_L";
  EXPECT_EQ(blamed_by_prediction(c, 0.9, 0.1), "lowest_breast_L");
  c.right = "acromion_R";
  c.left = "acromion_L";
  c.blamed = "acromion_L";
  c.distance_mm = 15.0;  // within the tolerance: nobody is flagged by the pair, the blame is left as it is
  EXPECT_EQ(blamed_by_prediction(c, 0.9, 0.1), "acromion_L");
}

TEST(BilateralCheck, NeedsTheSternumAndTwoOtherPairs) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  auto landmarks = truth_targets(c);
  std::vector<LandmarkTarget> no_notch;
  for (const auto& t : landmarks)
    if (t.name != "sternal_notch") no_notch.push_back(t);
  EXPECT_TRUE(check_bilateral_pairs(no_notch, 15.0).empty());
  std::vector<LandmarkTarget> two_pairs;  // acromia and mid-axillary points: each has one other pair
  for (const auto& t : landmarks)
    if (t.name.rfind("acromion_", 0) == 0 || t.name.rfind("midaxillary_", 0) == 0 || t.name == "sternal_notch" ||
        t.name == "xiphoid")
      two_pairs.push_back(t);
  EXPECT_TRUE(check_bilateral_pairs(two_pairs, 15.0).empty());
  EXPECT_FALSE(bilateral_tolerance_mm("nipple_", 15.0).has_value());
  EXPECT_FALSE(bilateral_tolerance_mm("pectoral_insertion_", 15.0).has_value());
  EXPECT_DOUBLE_EQ(bilateral_tolerance_mm("acromion_", 30.0)->x(), 2.0 * bilateral_tolerance_mm("acromion_", 15.0)->x());
}

// Session 24: a pair beyond its tolerance whose members are about as far from the typical
// proportions (margin below 5 mm), and whose predictions do not decide, cannot tell which of the two
// is off; a clear margin, a deciding prediction or a pair within its tolerance can.
TEST(BilateralCheck, ABlameThePairCannotMakeIsUncertain) {
  BilateralCheck c = acromia_beyond_tolerance();
  c.blame_margin_mm = 3.0;
  EXPECT_TRUE(blame_is_uncertain(c, 0.2, 0.3));
  EXPECT_FALSE(blame_is_uncertain(c, 0.6, 0.1));  // the right one's prediction moved: it is blamed
  c.blame_margin_mm = 8.0;
  EXPECT_FALSE(blame_is_uncertain(c, 0.2, 0.3));  // the proportions tell
  c.blame_margin_mm = 3.0;
  c.distance_mm = 15.0;
  EXPECT_FALSE(blame_is_uncertain(c, 0.2, 0.3));  // within the tolerance: nobody is flagged by the pair
  c.distance_mm = 30.0;
  c.right = "lowest_breast_R";  // predictions never decide for the lowest breast points
  c.left = "lowest_breast_L";
  EXPECT_TRUE(blame_is_uncertain(c, 0.9, 0.1));
}

// The blame margin is how much farther from the pair's typical proportions the blamed one is.
TEST(BilateralCheck, TheBlameMarginIsTheDifferenceOfTheProportions) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  const auto margin_after = [&](double mm) {
    auto landmarks = truth_targets(c);
    move(landmarks, "acromion_R", mm * f.up);
    const BilateralCheck* off = pair_of(check_bilateral_pairs(landmarks, 15.0), "acromion_R");
    EXPECT_NE(off, nullptr);
    if (!off) return 0.0;
    EXPECT_TRUE(off->flagged());
    EXPECT_EQ(off->axis, "vertically");
    EXPECT_EQ(off->blamed, "acromion_R");
    return off->blame_margin_mm;
  };
  // 10 mm further up: 10 mm farther from the typical proportions, the partner where it was.
  EXPECT_NEAR(margin_after(35.0) - margin_after(25.0), 10.0, 1.0);
}

}  // namespace
}  // namespace breastfit::fit
