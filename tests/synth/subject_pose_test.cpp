#include "breastfit/synth/subject_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "breastfit/template/default_template.h"
#include "support/toy_model.h"

namespace breastfit::synth {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(SubjectPose, WithinBoundsAndDeterministic) {
  const auto model = test::make_toy_model();
  SynthOptions o;
  o.subject.shape_amplitude = 1.0;
  Rng r1(3), r2(3);
  const SubjectPose a = sample_subject_pose(model, o, r1);
  const SubjectPose b = sample_subject_pose(model, o, r2);
  EXPECT_TRUE(a.params.alpha == b.params.alpha);
  EXPECT_TRUE(a.arms.empty());  // the toy has no arms
  EXPECT_NEAR(a.params.global.scale, 1.0, o.subject.global_scale_range + 1e-12);
  EXPECT_TRUE(a.params.global.rotation.isApprox(Quat::Identity()));
  EXPECT_EQ(a.params.global.translation, Vec3::Zero());
  for (int k = 0; k < model.num_blendshapes(); ++k) {
    EXPECT_GE(a.params.alpha[k], model.blendshapes[k].lo);
    EXPECT_LE(a.params.alpha[k], model.blendshapes[k].hi);
  }
  EXPECT_GT(a.params.alpha.cwiseAbs().maxCoeff(), 0.0);
  for (int j = 0; j < model.num_bones(); ++j) {
    const auto& bp = a.params.bones[static_cast<size_t>(j)];
    for (int ax = 0; ax < 3; ++ax) {
      EXPECT_GE(bp.scale[ax], model.bones[j].scale_lo[ax]);
      EXPECT_LE(bp.scale[ax], model.bones[j].scale_hi[ax]);
      EXPECT_LE(std::abs(bp.scale[ax] - 1.0), o.subject.bone_scale_range + 1e-12);
    }
    EXPECT_LE(Eigen::AngleAxisd(bp.rotation).angle(), o.subject.bone_rotation_deg * kDeg + 1e-9);
  }
  SynthOptions zero;
  zero.subject.shape_amplitude = 0.0;
  Rng r3(3);
  EXPECT_EQ(sample_subject_pose(model, zero, r3).params.alpha.cwiseAbs().maxCoeff(), 0.0);
}

TEST(SubjectPose, ArmsReachTheDrawnAbductionAndSupineShiftsTheBreasts) {
  const auto model = templ::build_default_template();
  for (PoseType pose : {PoseType::Standing, PoseType::Supine}) {
    SynthOptions o;
    o.pose = pose;
    o.subject.standing_flexion_deg = {0, 0};
    o.subject.supine_flexion_deg = {0, 0};
    Rng rng(17);
    const SubjectPose s = sample_subject_pose(model, o, rng);
    ASSERT_EQ(s.arms.size(), 2u);
    const Range want = pose == PoseType::Standing ? o.subject.standing_abduction_deg : o.subject.supine_abduction_deg;
    for (const ArmPose& a : s.arms) {
      EXPECT_GE(a.abduction_deg, want.lo);
      EXPECT_LE(a.abduction_deg, want.hi);
      const int j = *model.bone_index("upper_arm_" + a.side);
      Vec3 dir = model.bones[j].axes.col(0);
      if (dir.z() > 0) dir = -dir;
      const Vec3 posed = s.params.bones[static_cast<size_t>(j)].rotation * dir;
      EXPECT_NEAR(std::atan2(std::abs(posed.x()), -posed.z()) / kDeg, a.abduction_deg, 1e-6) << a.side;
      // The arm goes outwards: its x has the side's sign.
      EXPECT_EQ(posed.x() < 0, model.bones[j].pivot.x() < 0);
      // The joint point follows the clavicle.
      const int c = *model.bone_index("clavicle_" + a.side);
      const auto& cp = s.params.bones[static_cast<size_t>(c)];
      const auto& ap = s.params.bones[static_cast<size_t>(j)];
      const Vec3 by_clavicle = cp.rotation * (model.bones[j].pivot - model.bones[c].pivot) + model.bones[c].pivot;
      EXPECT_LT((model.bones[j].pivot + ap.translation - by_clavicle).norm(), 1e-9);
    }
    if (pose == PoseType::Supine) {
      ASSERT_FALSE(s.supine_shapes.empty());
      const int lat = *model.blendshape_index("breast_lateral_R");
      EXPECT_GE(s.params.alpha[lat], 0.6 * model.blendshapes[lat].hi - 1e-12);
    } else {
      EXPECT_TRUE(s.supine_shapes.empty());
    }
  }
}

}  // namespace
}  // namespace breastfit::synth
