#include "breastfit/synth/synth_options.h"

#include <gtest/gtest.h>

#include <cmath>

#include "breastfit/core/errors.h"

namespace breastfit::synth {
namespace {

TEST(SynthOptions, DefaultsAreValid) {
  SynthOptions o;
  EXPECT_NO_THROW(o.validate());
  o.pose = PoseType::Supine;
  o.units = "m";
  EXPECT_NO_THROW(o.validate());
}

TEST(SynthOptions, RejectsBadValuesNamingTheField) {
  auto expect_bad = [](auto mutate, const std::string& field) {
    SynthOptions o;
    mutate(o);
    try {
      o.validate();
      ADD_FAILURE() << "no exception for " << field;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  expect_bad([](SynthOptions& o) { o.units = "cm"; }, "units");
  expect_bad([](SynthOptions& o) { o.subject.shape_amplitude = 1.5; }, "shape_amplitude");
  expect_bad([](SynthOptions& o) { o.subject.supine_abduction_deg = {90, 60}; }, "supine_abduction_deg");
  expect_bad([](SynthOptions& o) { o.deformation.n_bumps = -1; }, "n_bumps");
  expect_bad([](SynthOptions& o) { o.refinement.target_edge_mm = 0; }, "target_edge_mm");
  expect_bad([](SynthOptions& o) { o.scanner.n_azimuth = 0; }, "n_azimuth");
  expect_bad([](SynthOptions& o) { o.scanner.elevations_deg.clear(); }, "elevations_deg");
  expect_bad([](SynthOptions& o) { o.scanner.min_views = 1000; }, "min_views");
  expect_bad([](SynthOptions& o) { o.scanner.arc_deg_supine = 270; }, "arc_deg_supine");
  expect_bad([](SynthOptions& o) { o.artifacts.n_holes = -2; }, "n_holes");
  expect_bad([](SynthOptions& o) { o.artifacts.white_noise_mm = -0.1; }, "white_noise_mm");
  expect_bad([](SynthOptions& o) { o.artifacts.hole_radius_mm = {0.1, 5}; }, "hole_radius_mm");
  expect_bad([](SynthOptions& o) { o.misalign_rotation_deg = 400; }, "misalign_rotation_deg");
  expect_bad([](SynthOptions& o) { o.landmark_noise_mm = std::nan(""); }, "landmark_noise_mm");
}

TEST(SynthOptions, PoseNames) {
  EXPECT_EQ(parse_pose_type("standing"), PoseType::Standing);
  EXPECT_EQ(parse_pose_type("supine"), PoseType::Supine);
  EXPECT_EQ(pose_type_name(PoseType::Supine), "supine");
  EXPECT_THROW(parse_pose_type("prone"), InvalidInput);
}

}  // namespace
}  // namespace breastfit::synth
