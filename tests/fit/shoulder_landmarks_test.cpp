// The acromion, the mid-axillary point and the pectoral insertion placed on a synthetic supine scan by the sternum's
// proportions, from fitted points as far off as the landmark-free fit leaves them.
#include "breastfit/fit/shoulder_landmarks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fit/synth_anatomy.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;  // the synthetic torsos, their truth and body frame

SternumFrame sternum_frame(const synth::SynthCase& c, const std::string& side) {
  const Frame f = body_frame(c);
  SternumFrame s;
  s.notch = truth(c, "sternal_notch");
  s.length_mm = (truth(c, "sternal_notch") - truth(c, "xiphoid")).norm();
  s.up = f.up;
  s.front = f.front;
  s.lateral = f.up.cross(f.front);
  if (s.lateral.dot(truth(c, "nipple_L") - truth(c, "nipple_R")) < 0) s.lateral = -s.lateral;
  if (side == "R") s.lateral = -s.lateral;
  return s;
}

using InFrame = SternumCoordinates;

// No scan vertex `in` the strip scores higher than the point found.
template <class InStrip, class Score>
void expect_best_of_strip(const Points& V, const SternumFrame& f, const Vec3& found, InStrip in, Score score,
                          const char* side) {
  const double best = score(sternum_coordinates(f, found));
  for (Index i = 0; i < V.rows(); ++i) {
    const InFrame q = sternum_coordinates(f, V.row(i).transpose());
    if (in(q)) EXPECT_LE(score(q), best) << side;
  }
}

TEST(ShoulderLandmarks, SternumFrameFromTheNotchXiphoidAndNipples) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Supine);
  const Vec3 notch = truth(c, "sternal_notch"), xiphoid = truth(c, "xiphoid");
  const Vec3 right = truth(c, "nipple_R"), left = truth(c, "nipple_L");
  for (const char* side : {"R", "L"}) {
    const SternumFrame expected = sternum_frame(c, side);
    const auto f = fit::sternum_frame(notch, xiphoid, right, left, side[0]);
    ASSERT_TRUE(f) << side;
    EXPECT_TRUE(f->notch.isApprox(notch)) << side;
    EXPECT_NEAR(f->length_mm, expected.length_mm, 1e-9) << side;
    EXPECT_GT(f->up.dot(expected.up), 1 - 1e-9) << side;
    // Orthogonal to the sternum and to the nipples' line: the level front of the truth's frame when
    // the nipples are level.
    EXPECT_NEAR(f->front.norm(), 1.0, 1e-9) << side;
    EXPECT_NEAR(f->front.dot(f->up), 0.0, 1e-9) << side;
    EXPECT_NEAR(f->front.dot(left - right), 0.0, 1e-9) << side;
    EXPECT_GT(f->front.dot(expected.front), 0.95) << side;
    EXPECT_GT(f->lateral.dot(expected.lateral), 0.95) << side;  // towards the side asked for
  }
  // The nipples swapped: still in front, the sides swapped with them.
  const auto swapped = fit::sternum_frame(notch, xiphoid, left, right, 'L');
  ASSERT_TRUE(swapped);
  EXPECT_GT(swapped->front.dot(sternum_frame(c, "L").front), 0.95);
  EXPECT_GT(swapped->lateral.dot(sternum_frame(c, "R").lateral), 0.95);
  EXPECT_FALSE(fit::sternum_frame(notch, notch, right, left, 'R'));  // no sternum
  EXPECT_FALSE(fit::sternum_frame(notch, xiphoid, right, right, 'R'));  // no line through the nipples
}

TEST(ShoulderLandmarks, MidaxillaryPointOnTheChestWallAtTheSternumsProportion) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Supine);
  const ShoulderLandmarkOptions o;
  for (const char* side : {"R", "L"}) {
    const SternumFrame f = sternum_frame(c, side);
    const Vec3 truth_point = truth(c, std::string("midaxillary_") + side);
    const Vec3 fitted = truth_point + 15.0 * f.up;  // risen with the abducted arm
    const auto found = midaxillary_on_scan(c.scan.V, fitted, f);
    ASSERT_TRUE(found) << side;
    const Vec3 d = *found - f.notch;
    EXPECT_NEAR(d.dot(f.up), -o.midaxillary_drop * f.length_mm, o.strip_half_width_mm) << side;
    EXPECT_NEAR(d.dot(f.front), (fitted - f.notch).dot(f.front), o.strip_half_width_mm) << side;
    // On the side of the chest: of the strip's vertices, the one nearest the fitted point across
    // the body (not the other side, not the arm beyond the chest wall).
    EXPECT_GT(d.dot(f.lateral), 0.5 * f.length_mm) << side;
    const InFrame a = sternum_coordinates(f, fitted);
    const double height = -o.midaxillary_drop * f.length_mm, w = o.strip_half_width_mm;
    expect_best_of_strip(
        c.scan.V, f, *found,
        [&](const InFrame& q) { return std::abs(q.height - height) <= w && std::abs(q.front - a.front) <= w; },
        [&](const InFrame& q) { return -std::abs(q.lateral - a.lateral); }, side);
  }
}

TEST(ShoulderLandmarks, AcromionOnTopOfTheShoulderAtTheSternumsProportion) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Supine);
  const ShoulderLandmarkOptions o;
  for (const char* side : {"R", "L"}) {
    const SternumFrame f = sternum_frame(c, side);
    const Vec3 fitted = truth(c, std::string("acromion_") + side);
    const auto found = acromion_on_scan(c.scan.V, fitted, f);
    ASSERT_TRUE(found) << side;
    const Vec3 d = *found - f.notch;
    const double breadth = o.acromion_breadth * f.length_mm;
    EXPECT_NEAR(d.dot(f.lateral), breadth, o.strip_half_width_mm) << side;
    // The top of the strip: no scan vertex in it lies higher.
    const InFrame a = sternum_coordinates(f, fitted);
    const double w = o.strip_half_width_mm;
    expect_best_of_strip(
        c.scan.V, f, *found,
        [&](const InFrame& q) {
          return std::abs(q.lateral - breadth) <= w && std::abs(q.front - a.front) <= w &&
                 std::abs(q.height - a.height) <= o.acromion_height_window_mm;
        },
        [](const InFrame& q) { return q.height; }, side);
  }
}

TEST(ShoulderLandmarks, PectoralInsertionOnTheFrontOfTheArmAtTheSternumsProportion) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Supine);
  const ShoulderLandmarkOptions o;
  for (const char* side : {"R", "L"}) {
    const SternumFrame f = sternum_frame(c, side);
    const auto found = abducted_pectoral_insertion_on_scan(c.scan.V, f);
    ASSERT_TRUE(found) << side;
    const Vec3 d = *found - f.notch;
    const double breadth = o.pectoral_breadth * f.length_mm, height = -o.pectoral_drop * f.length_mm;
    EXPECT_NEAR(d.dot(f.lateral), breadth, o.strip_half_width_mm) << side;
    EXPECT_NEAR(d.dot(f.up), height, o.strip_half_width_mm) << side;
    // The front of the strip: no scan vertex in it lies farther forward.
    const double w = o.strip_half_width_mm;
    expect_best_of_strip(
        c.scan.V, f, *found,
        [&](const InFrame& q) { return std::abs(q.lateral - breadth) <= w && std::abs(q.height - height) <= w; },
        [](const InFrame& q) { return q.front; }, side);
  }
}

TEST(ShoulderLandmarks, HangingPectoralInsertionOnTheArmsFrontAtTheSternumsProportion) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const ShoulderLandmarkOptions o;
  for (const char* side : {"R", "L"}) {
    const SternumFrame f = sternum_frame(c, side);
    // The arm's front as the anterior axillary fold gives it: about 8 mm too low.
    const Vec3 arm_front = truth(c, std::string("pectoral_insertion_") + side) - 8.0 * f.up;
    const auto found = hanging_pectoral_insertion_on_scan(c.scan.V, arm_front, f);
    ASSERT_TRUE(found) << side;
    const Vec3 d = *found - f.notch, a = arm_front - f.notch;
    const double height = -o.hanging_pectoral_drop * f.length_mm;
    EXPECT_NEAR(d.dot(f.up), height, o.strip_half_width_mm) << side;
    EXPECT_NEAR(d.dot(f.lateral), a.dot(f.lateral), o.strip_half_width_mm) << side;
    // The front of the strip (behind the arm's front only so far): no scan vertex in it lies
    // farther forward.
    const double w = o.strip_half_width_mm;
    expect_best_of_strip(
        c.scan.V, f, *found,
        [&](const InFrame& q) {
          return std::abs(q.height - height) <= w && std::abs(q.lateral - a.dot(f.lateral)) <= w &&
                 q.front > a.dot(f.front) - o.max_behind_mm;
        },
        [](const InFrame& q) { return q.front; }, side);
  }
  EXPECT_FALSE(hanging_pectoral_insertion_on_scan(Points(0, 3), truth(c, "pectoral_insertion_R"), sternum_frame(c, "R")));
}

TEST(ShoulderLandmarks, ArmsAbductedOnTheScanOfASupineTorsoOnly) {
  const synth::SynthCase& supine = synth_case(synth::PoseType::Supine);
  const synth::SynthCase& standing = synth_case(synth::PoseType::Standing);
  EXPECT_TRUE(arms_abducted_on_scan(supine.scan.V, sternum_frame(supine, "R")));
  EXPECT_TRUE(arms_abducted_on_scan(supine.scan.V, sternum_frame(supine, "L")));
  EXPECT_FALSE(arms_abducted_on_scan(standing.scan.V, sternum_frame(standing, "R")));
  // One arm cut away: not both arms out.
  const SternumFrame f = sternum_frame(supine, "R");
  Points one_arm(supine.scan.V.rows(), 3);
  Index n = 0;
  for (Index i = 0; i < supine.scan.V.rows(); ++i)
    if (sternum_coordinates(f, supine.scan.V.row(i).transpose()).lateral < 0.9 * f.length_mm)
      one_arm.row(n++) = supine.scan.V.row(i);
  one_arm.conservativeResize(n, 3);
  EXPECT_FALSE(arms_abducted_on_scan(one_arm, f));
  EXPECT_FALSE(arms_abducted_on_scan(Points(0, 3), f));
}

TEST(ShoulderLandmarks, RefusesWhenUnsure) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Supine);
  const SternumFrame f = sternum_frame(c, "R");
  const Vec3 midaxillary = truth(c, "midaxillary_R"), acromion = truth(c, "acromion_R");
  // No scan.
  EXPECT_FALSE(midaxillary_on_scan(Points(0, 3), midaxillary, f));
  EXPECT_FALSE(acromion_on_scan(Points(0, 3), acromion, f));
  // A fitted point far from where the proportions put it (the point found would move too far).
  EXPECT_FALSE(midaxillary_on_scan(c.scan.V, midaxillary + 60.0 * f.up, f));
  EXPECT_FALSE(acromion_on_scan(c.scan.V, acromion + 60.0 * f.up + 60.0 * f.lateral, f));
  // No sternum.
  SternumFrame degenerate = f;
  degenerate.length_mm = 0;
  EXPECT_FALSE(midaxillary_on_scan(c.scan.V, midaxillary, degenerate));
  EXPECT_FALSE(acromion_on_scan(c.scan.V, acromion, degenerate));
  EXPECT_FALSE(abducted_pectoral_insertion_on_scan(c.scan.V, degenerate));
  EXPECT_FALSE(abducted_pectoral_insertion_on_scan(Points(0, 3), f));
}

}  // namespace
}  // namespace breastfit::fit
