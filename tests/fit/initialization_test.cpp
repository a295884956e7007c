// The similarity from landmarks, and a mirrored set (every _R/_L label exchanged) diagnosed and
// corrected, on a synthetic scan made from the template; the arms' angle search on the template
// posed with its arms raised.
#include "breastfit/fit/initialization.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <tuple>
#include <utility>

#include "breastfit/fit/registration.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/landmark_names.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/synth/synth_case.h"
#include "support/default_template.h"

namespace breastfit::fit {
namespace {

std::vector<LandmarkTarget> synth_targets(bool mirrored) {
  synth::SynthOptions o;
  o.seed = 21;
  const synth::SynthCase c = synth::make_case(*test::default_template(), o);
  std::vector<std::pair<std::string, Vec3>> named;
  for (const auto& p : c.input_landmarks) named.emplace_back(mirrored ? mirrored_landmark_name(p.name) : p.name, p.position);
  return match_landmarks(*test::default_template(), named);
}

TEST(Initialization, LandmarksAsGivenAreNotSwapped) {
  auto targets = synth_targets(false);
  const auto before = targets;
  const LandmarkInitialization init = initialize_from_landmarks(*test::default_template(), targets);
  EXPECT_FALSE(init.swapped);
  EXPECT_LT(init.rms_mm, 40.0);
  for (size_t i = 0; i < targets.size(); ++i) EXPECT_EQ(targets[i].name, before[i].name);
}

TEST(Initialization, AMirroredSetIsDiagnosedAndRelabelled) {
  auto targets = synth_targets(true);
  const LandmarkInitialization init = initialize_from_landmarks(*test::default_template(), targets);
  ASSERT_TRUE(init.swapped);
  EXPECT_GT(init.swapped_rms_mm, 2 * init.rms_mm);  // as given vs corrected
  // Back to the true labels: the nipple labelled "nipple_R" is the patient's right one again.
  const auto correct = synth_targets(false);
  for (const auto& t : targets)
    for (const auto& u : correct)
      if (u.name == t.name) EXPECT_LT((u.position - t.position).norm(), 1e-9) << t.name;
}

// A scan that is the template itself with its upper arms raised by (R, L) degrees (about the
// antero-posterior axis, as initialize_arms turns them).
TriangleMesh arms_raised(double right_deg, double left_deg) {
  const auto& model = *test::default_template();
  model::PoseParams params = model::PoseParams::identity(model);
  for (const auto& [name, deg, sign] : {std::tuple{"upper_arm_R", right_deg, 1.0}, std::tuple{"upper_arm_L", left_deg, -1.0}}) {
    const int bone = *model.bone_index(name);
    params.bones[bone].rotation =
        Quat(Eigen::AngleAxisd(sign * deg * M_PI / 180.0, Vec3::UnitY())) * params.bones[bone].rotation;
  }
  model::PoseEvaluator ev(model);
  ev.set_params(params);
  TriangleMesh scan;
  scan.V = ev.vertices();
  scan.F = model.rest.F;
  return scan;
}

// The coarse pass scores every second angle (20° apart), the fine pass the two beside the best:
// angles the coarse pass skips (50°, −30°), one it scores (80°) and the last (90°) are all found,
// with one thread and with two.
TEST(Initialization, TheArmsAreRaisedToTheScansAngles) {
  const auto& model = *test::default_template();
  for (const auto& [right, left] : {std::pair{50.0, 80.0}, std::pair{-30.0, 90.0}, std::pair{0.0, 20.0}}) {
    const ScanTarget scan(arms_raised(right, left), 800);
    for (const int threads : {1, 2}) {
      model::PoseParams params = model::PoseParams::identity(model);
      const std::array<double, 2> raised = initialize_arms(model, scan, params, false, threads);
      EXPECT_EQ(raised[0], right) << "right arm, " << threads << " threads";
      EXPECT_EQ(raised[1], left) << "left arm, " << threads << " threads";
    }
  }
}

}  // namespace
}  // namespace breastfit::fit
