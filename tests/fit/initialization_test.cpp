// The similarity from landmarks, and a mirrored set (every _R/_L label exchanged) diagnosed and
// corrected, on a synthetic scan made from the template.
#include "breastfit/fit/initialization.h"

#include <gtest/gtest.h>

#include "breastfit/fit/registration.h"
#include "breastfit/mesh/landmark_names.h"
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

}  // namespace
}  // namespace breastfit::fit
