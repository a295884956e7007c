// The pectoral insertion found on a chest-and-arm surface from a fitted point as far off as the fit
// leaves it without the landmark (too low and too medial, arms hanging); refusals with no crease,
// the arms abducted (a synthetic supine torso), a hole over the fold or no scan; and the arm's axis
// on the posed template. (On the template-made synthetic torsos the template's own insertion is
// the truth, which is where the fit already puts it: they test the refusals, not the accuracy.)
#include "breastfit/fit/pectoral_insertion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "breastfit/model/pose_evaluator.h"
#include "fit/synth_anatomy.h"

namespace breastfit::fit {
namespace {

using namespace test_anatomy;  // the synthetic torsos, their truth and body frame

struct Side {
  std::string name;  // "R" or "L"
  Vec3 insertion, nipple, arm, medial;
};

// The truth insertion and nipple of one side, the arm's axis on the true pose, the medial direction.
Side side_of(const synth::SynthCase& c, const std::string& side) {
  const model::RiggedModel& model = *test::default_template();
  const Points V = model::pose_vertices(model, c.true_params_scan);
  const auto arm = upper_arm_axis(model, V, c.true_params_scan, side);
  EXPECT_TRUE(arm) << side;
  Side s{side, truth(c, "pectoral_insertion_" + side), truth(c, "nipple_" + side), arm.value_or(Vec3::Zero()),
         Vec3::Zero()};
  const Frame f = body_frame(c);
  s.medial = f.up.cross(f.front);  // towards the body's left
  if (side == "L") s.medial = -s.medial;
  return s;
}

TEST(PectoralInsertion, TheArmAxisPointsFromTheShoulderDown) {
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  for (const char* name : {"R", "L"}) {
    const Side s = side_of(c, name);
    EXPECT_NEAR(s.arm.norm(), 1.0, 1e-9);
    EXPECT_GT(-s.arm.dot(f.up), 0.8) << name;  // arms hanging: mostly downwards
  }
  const model::RiggedModel& model = *test::default_template();
  EXPECT_FALSE(upper_arm_axis(model, model::pose_vertices(model, c.true_params_scan), c.true_params_scan, "X"));
}

// Posing only the rows upper_arm_axis reads gives the same axis, bit for bit, as posing the whole
// mesh (the insertion's check poses only them at its leave-one-out step): both sides, both poses.
TEST(PectoralInsertion, TheArmAxisFromItsRowsAloneIsTheSameBits) {
  const model::RiggedModel& model = *test::default_template();
  for (const auto pose : {synth::PoseType::Standing, synth::PoseType::Supine}) {
    const synth::SynthCase& c = synth_case(pose);
    model::PoseEvaluator ev(model);
    ev.set_params(c.true_params_scan);
    for (const char* side : {"R", "L"}) {
      const std::vector<Index> rows = upper_arm_axis_rows(model, side);
      ASSERT_GT(rows.size(), 10u) << side;
      EXPECT_TRUE(std::is_sorted(rows.begin(), rows.end()));
      Points V = Points::Zero(model.rest.V.rows(), 3);
      ev.pose_rows(c.true_params_scan, rows, V);
      const auto whole = upper_arm_axis(model, ev.vertices(), c.true_params_scan, side);
      const auto alone = upper_arm_axis(model, V, c.true_params_scan, side);
      ASSERT_TRUE(whole && alone) << side;
      EXPECT_EQ(*whole, *alone) << side;
    }
  }
  EXPECT_TRUE(upper_arm_axis_rows(model, "X").empty());
}

// A chest and a hanging arm seen from the front (x lateral, y anterior, z up, mm): the chest's
// front recedes laterally, the arm is a vertical cylinder beside it (front at x = 150, y = 40);
// above z = 0 the fold bridges them (a straight skin from the chest to the arm's front), below it
// the axilla's gap opens between them. The insertion is the arm's front at the fold's lower border.
Points chest_and_arm(bool fold_everywhere) {
  std::vector<Vec3> p;
  for (double z = -100; z <= 100; z += 2) {
    for (double x = 0; x <= 115; x += 2) p.emplace_back(x, 60 - 0.004 * x * x, z);
    for (double deg = -90; deg <= 90; deg += 3)
      p.emplace_back(150 + 40 * std::sin(deg * M_PI / 180), 40 * std::cos(deg * M_PI / 180), z);
    if (z >= 0 || fold_everywhere)
      for (double x = 90; x <= 150; x += 2) p.emplace_back(x, 27.6 + (x - 90) * 12.4 / 60, z);
  }
  Points out(static_cast<Index>(p.size()), 3);
  for (size_t i = 0; i < p.size(); ++i) out.row(static_cast<Index>(i)) = p[i].transpose();
  return out;
}

const Vec3 kUp(0, 0, 1), kFront(0, 1, 0), kDown(0, 0, -1), kNipple(50, 50, -60), kInsertion(150, 40, 0);

TEST(PectoralInsertion, FindsTheArmsFrontAtTheFoldsLowerBorder) {
  const Points scan = chest_and_arm(false);
  double sum = 0, start = 0;
  // Too low and too medial (as the fit leaves it), and too high.
  for (const Vec3& off : {Vec3(-8, 0, -14), Vec3(-4, -2, -8), Vec3(-6, 0, 8), Vec3(0, 0, 20)}) {
    const auto found = pectoral_insertion_on_scan(scan, kInsertion + off, kDown, kUp, kFront, kNipple);
    ASSERT_TRUE(found) << off.transpose();
    const double error = (*found - kInsertion).norm();
    EXPECT_LE(error, 5.0) << off.transpose() << ": " << found->transpose();  // first creased slice (3 mm), 2 mm grid
    sum += error;
    start += off.norm();
  }
  EXPECT_LT(sum, 0.3 * start);
}

TEST(PectoralInsertion, RefusesWithoutACreaseOrFarFromTheFittedPoint) {
  // The fold bridging chest and arm all the way down: no crease.
  EXPECT_FALSE(pectoral_insertion_on_scan(chest_and_arm(true), kInsertion, kDown, kUp, kFront, kNipple));
  // The fitted point 45 mm below the fold: the first creased slice is already far from it.
  EXPECT_FALSE(pectoral_insertion_on_scan(chest_and_arm(false), kInsertion + Vec3(0, 0, -45) + Vec3(-10, 0, 0), kDown,
                                          kUp, kFront, kNipple));
  // The arm abducted 70° (on an arm board).
  const Vec3 abducted = Vec3(std::sin(70 * M_PI / 180), 0, -std::cos(70 * M_PI / 180));
  EXPECT_FALSE(pectoral_insertion_on_scan(chest_and_arm(false), kInsertion, abducted, kUp, kFront, kNipple));
}

TEST(PectoralInsertion, RefusesArmsAbductedHolesAndNoScan) {
  // Supine, arms on boards: the arm leaves the chest sideways.
  {
    const synth::SynthCase& c = synth_case(synth::PoseType::Supine);
    const Frame f = body_frame(c);
    for (const char* name : {"R", "L"}) {
      const Side s = side_of(c, name);
      EXPECT_FALSE(pectoral_insertion_on_scan(c.scan.V, s.insertion, s.arm, f.up, f.front, s.nipple)) << name;
    }
  }
  const synth::SynthCase& c = synth_case(synth::PoseType::Standing);
  const Frame f = body_frame(c);
  const Side s = side_of(c, "L");
  const Vec3 fitted = s.insertion - 10.0 * f.up + 6.0 * s.medial;
  // A hole over the front of the shoulder and the arm (the fold unseen).
  Points holed(c.scan.V.rows(), 3);
  Index n = 0;
  for (Index i = 0; i < c.scan.V.rows(); ++i)
    if ((c.scan.V.row(i).transpose() - fitted).norm() > 80.0) holed.row(n++) = c.scan.V.row(i);
  holed.conservativeResize(n, 3);
  EXPECT_FALSE(pectoral_insertion_on_scan(holed, fitted, s.arm, f.up, f.front, s.nipple));
  // No scan; a degenerate arm axis (along the body's front).
  EXPECT_FALSE(pectoral_insertion_on_scan(Points(0, 3), fitted, s.arm, f.up, f.front, s.nipple));
  EXPECT_FALSE(pectoral_insertion_on_scan(c.scan.V, fitted, f.front, f.up, f.front, s.nipple));
}

}  // namespace
}  // namespace breastfit::fit
