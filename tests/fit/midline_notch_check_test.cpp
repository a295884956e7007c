// The sternal notch checked against its anatomical definition: the midsagittal plane of the other
// landmarks, and the jugular notch found on the scan on that plane — on synthetic scans, with the
// notch as given and moved 20–30 mm along the skin.
#include "breastfit/fit/midline_notch_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fit/synth_anatomy.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;  // the synthetic torsos, their truth and body frame

double plane_distance(const MidPlane& plane, const Vec3& p) { return std::abs((p - plane.point).dot(plane.normal)); }

TEST(MidlineNotchCheck, MidplaneOfTheLandmarksIsTheBodysMidline) {
  for (const auto pose : {synth::PoseType::Standing, synth::PoseType::Supine}) {
    const synth::SynthCase& c = synth_case(pose);
    const Frame f = body_frame(c);
    const auto plane = landmark_midplane(truth_targets(c), "sternal_notch");
    ASSERT_TRUE(plane) << synth::pose_type_name(pose);
    // Normal right → left: perpendicular to the body's up and front axes, pointing to nipple_L.
    EXPECT_LT(std::abs(plane->normal.dot(f.up)), 0.1) << synth::pose_type_name(pose);
    EXPECT_LT(std::abs(plane->normal.dot(f.front)), 0.1) << synth::pose_type_name(pose);
    EXPECT_GT((truth(c, "nipple_L") - truth(c, "nipple_R")).dot(plane->normal), 0) << synth::pose_type_name(pose);
    // The midline landmarks lie on it (the notch was left out of it).
    EXPECT_LT(plane_distance(*plane, truth(c, "sternal_notch")), 6.0) << synth::pose_type_name(pose);
    EXPECT_LT(plane_distance(*plane, truth(c, "xiphoid")), 6.0) << synth::pose_type_name(pose);
  }
}

TEST(MidlineNotchCheck, MidplaneLeavesOutTheSkippedLandmarkAndNeedsAPair) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  std::vector<LandmarkTarget> given = truth_targets(c);
  // A notch moved 30 mm to the side does not move the plane it is checked against.
  for (auto& t : given)
    if (t.name == "sternal_notch") t.position += 30.0 * (truth(c, "nipple_L") - truth(c, "nipple_R")).normalized();
  const auto with = landmark_midplane(given, "");
  const auto without = landmark_midplane(given, "sternal_notch");
  ASSERT_TRUE(with && without);
  EXPECT_GT(plane_distance(*with, truth(c, "xiphoid")), plane_distance(*without, truth(c, "xiphoid")));
  EXPECT_LT(plane_distance(*without, truth(c, "xiphoid")), 6.0);
  // Only midline landmarks, or one side of each pair: no right → left direction, no plane.
  std::vector<LandmarkTarget> midline, one_side;
  for (const auto& t : given) {
    if (t.name == "sternal_notch" || t.name == "xiphoid") midline.push_back(t);
    if (t.name.back() != 'L') one_side.push_back(t);
  }
  EXPECT_FALSE(landmark_midplane(midline));
  EXPECT_FALSE(landmark_midplane(one_side));
  // A pair skipped through one of its members is left out.
  std::vector<LandmarkTarget> nipples;
  for (const auto& t : given)
    if (t.name == "nipple_R" || t.name == "nipple_L") nipples.push_back(t);
  EXPECT_TRUE(landmark_midplane(nipples));
  EXPECT_FALSE(landmark_midplane(nipples, "nipple_R"));
}

// The notch found from a start `off` away (the prediction, which follows a wrong click part-way),
// and its distance to the given notch moved `moved` along the skin.
void expect_notch_checked(synth::PoseType pose) {
  const synth::SynthCase& c = synth_case(pose);
  const Frame f = body_frame(c);
  const Vec3 side = f.up.cross(f.front);
  const Vec3 notch = truth(c, "sternal_notch");
  const std::vector<LandmarkTarget> given = truth_targets(c);
  // Started on the notch, or 10 mm to a side, or 8 mm low: the found notch is the true one.
  for (const Vec3& start : {notch, Vec3(notch + 10.0 * side), Vec3(notch - 10.0 * side), Vec3(notch - 8.0 * f.up)}) {
    const auto found = midline_notch_on_scan(c.scan.V, given, start, f.up, f.front);
    ASSERT_TRUE(found) << synth::pose_type_name(pose) << " from " << start.transpose();
    EXPECT_LT((*found - notch).norm(), 10.0) << synth::pose_type_name(pose) << " from " << start.transpose();
  }
  // A notch clicked 25 mm to either side: the prediction follows it half-way, the midline holds,
  // and the found notch is farther from the click than the check's 14 mm.
  for (const double s : {-25.0, 25.0}) {
    const Vec3 clicked = notch + s * side;
    const auto found = midline_notch_on_scan(c.scan.V, given, notch + 0.5 * s * side, f.up, f.front);
    ASSERT_TRUE(found) << synth::pose_type_name(pose) << " " << s;
    EXPECT_GT((*found - clicked).norm(), 14.0) << synth::pose_type_name(pose) << " " << s;
  }
}

TEST(MidlineNotchCheck, FindsTheNotchOnTheMidlineStanding) { expect_notch_checked(synth::PoseType::Standing); }

TEST(MidlineNotchCheck, FindsTheNotchOnTheMidlineSupine) { expect_notch_checked(synth::PoseType::Supine); }

TEST(MidlineNotchCheck, RefusesWithoutAMidplaneOrAScan) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  const Vec3 notch = truth(c, "sternal_notch");
  std::vector<LandmarkTarget> midline;
  for (const auto& t : truth_targets(c))
    if (t.name == "sternal_notch" || t.name == "xiphoid") midline.push_back(t);
  EXPECT_FALSE(midline_notch_on_scan(c.scan.V, midline, notch, f.up, f.front));
  EXPECT_FALSE(midline_notch_on_scan(Points(0, 3), truth_targets(c), notch, f.up, f.front));
}

TEST(MidlineNotchCheck, ToleranceIsWiderVerticallyThanSideways) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  const Vec3 side = f.up.cross(f.front);
  const Vec3 notch = truth(c, "sternal_notch");
  const std::vector<LandmarkTarget> given = truth_targets(c);
  const auto found = midline_notch_on_scan(c.scan.V, given, notch, f.up, f.front);
  ASSERT_TRUE(found);
  // Given 15 mm from the found notch: flagged sideways (tolerance 12), not vertically (18).
  const auto sideways = check_notch_on_midline(c.scan.V, given, notch, f.up, f.front, *found + 15.0 * side, 12.0);
  const auto vertical = check_notch_on_midline(c.scan.V, given, notch, f.up, f.front, *found + 15.0 * f.up, 12.0);
  const auto diagonal = check_notch_on_midline(c.scan.V, given, notch, f.up, f.front,
                                               *found + 15.0 * (side + f.up).normalized(), 12.0);
  ASSERT_TRUE(sideways && vertical && diagonal);
  EXPECT_NEAR(sideways->distance_mm, 15.0, 1e-9);
  EXPECT_NEAR(sideways->tolerance_mm, 12.0, 1e-6);
  EXPECT_TRUE(sideways->flagged());
  EXPECT_NEAR(vertical->tolerance_mm, 18.0, 1e-6);
  EXPECT_FALSE(vertical->flagged());
  EXPECT_GT(diagonal->tolerance_mm, 12.0);
  EXPECT_LT(diagonal->tolerance_mm, 18.0);
  // 25 mm up or down: flagged.
  EXPECT_TRUE(check_notch_on_midline(c.scan.V, given, notch, f.up, f.front, *found - 25.0 * f.up, 12.0)->flagged());
  // Not found: no check.
  EXPECT_FALSE(check_notch_on_midline(Points(0, 3), given, notch, f.up, f.front, notch, 12.0));
}

}  // namespace
}  // namespace breastfit::fit
