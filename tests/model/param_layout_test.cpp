#include "breastfit/model/param_layout.h"

#include <gtest/gtest.h>

#include <set>

#include "breastfit/core/errors.h"
#include "breastfit/model/rigged_model.h"
#include "support/toy_model.h"

namespace breastfit::model {
namespace {

TEST(ParamLayout, SizesOffsetsAndKinds) {
  const RiggedModel m = test::make_toy_model();
  const ParamLayout layout(m);
  EXPECT_EQ(layout.num_bones(), 4);
  EXPECT_EQ(layout.num_blendshapes(), 6);
  EXPECT_EQ(layout.num_params(), 7 + 4 * 9 + 6);
  EXPECT_EQ(layout.bone_offset(2), 7 + 18);
  EXPECT_EQ(layout.blendshape_offset(1), 7 + 36 + 1);
  EXPECT_EQ(layout.kind(2), ParamKind::GlobalRotation);
  EXPECT_EQ(layout.kind(5), ParamKind::GlobalTranslation);
  EXPECT_EQ(layout.kind(6), ParamKind::GlobalScale);
  EXPECT_EQ(layout.kind(layout.bone_offset(1) + 2), ParamKind::BoneRotation);
  EXPECT_EQ(layout.kind(layout.bone_offset(1) + 4), ParamKind::BoneTranslation);
  EXPECT_EQ(layout.kind(layout.bone_offset(3) + 8), ParamKind::BoneScale);
  EXPECT_EQ(layout.kind(layout.blendshape_offset(5)), ParamKind::Blendshape);
  EXPECT_THROW(layout.kind(layout.num_params()), InvalidInput);
  EXPECT_THROW(layout.kind(-1), InvalidInput);
}

TEST(ParamLayout, NamesAreStableAndUnique) {
  const RiggedModel m = test::make_toy_model();
  const ParamLayout layout(m);
  EXPECT_EQ(layout.name(0), "global.rotation.x");
  EXPECT_EQ(layout.name(5), "global.translation.z");
  EXPECT_EQ(layout.name(6), "global.scale");
  EXPECT_EQ(layout.name(layout.bone_offset(2) + 0), "bone.chest.rotation.x");
  EXPECT_EQ(layout.name(layout.bone_offset(2) + 4), "bone.chest.translation.y");
  EXPECT_EQ(layout.name(layout.bone_offset(0) + 8), "bone.pelvis.scale.z");
  EXPECT_EQ(layout.name(layout.blendshape_offset(3)), "shape.breast_R");
  std::set<std::string> names;
  for (int q = 0; q < layout.num_params(); ++q) EXPECT_TRUE(names.insert(layout.name(q)).second) << layout.name(q);
}

TEST(ParamLayout, IncrementUpdatesEachBlock) {
  const RiggedModel m = test::make_toy_model();
  const ParamLayout layout(m);
  PoseParams p = PoseParams::identity(m);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(layout.num_params());
  d.segment<3>(0) = Vec3(0, 0, 0.5);
  d.segment<3>(3) = Vec3(1, 2, 3);
  d[6] = std::log(2.0);
  d.segment<3>(layout.bone_offset(1)) = Vec3(0.2, 0, 0);
  d.segment<3>(layout.bone_offset(1) + 3) = Vec3(-1, 0, 4);
  d.segment<3>(layout.bone_offset(1) + 6) = Vec3(0.1, -0.2, 0.3);
  d[layout.blendshape_offset(0)] = 0.25;
  layout.apply_increment(m, d, p);
  EXPECT_NEAR(p.global.rotation.angularDistance(Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()))), 0.0, 1e-12);
  EXPECT_TRUE(p.global.translation.isApprox(Vec3(1, 2, 3)));
  EXPECT_NEAR(p.global.scale, 2.0, 1e-12);
  EXPECT_NEAR(p.bones[1].rotation.angularDistance(Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX()))), 0.0, 1e-12);
  EXPECT_TRUE(p.bones[1].translation.isApprox(Vec3(-1, 0, 4)));
  EXPECT_TRUE(p.bones[1].scale.isApprox(Vec3(1.1, 0.8, 1.3)));
  EXPECT_DOUBLE_EQ(p.alpha[0], 0.25);
  EXPECT_TRUE(p.bones[0].scale.isApprox(Vec3::Ones()));

  // A second rotation increment is left-multiplied: exp(ω2) exp(ω1).
  Eigen::VectorXd d2 = Eigen::VectorXd::Zero(layout.num_params());
  d2.segment<3>(0) = Vec3(0.3, 0, 0);
  layout.apply_increment(m, d2, p);
  const Quat expected = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX())) * Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()));
  EXPECT_NEAR(p.global.rotation.angularDistance(expected), 0.0, 1e-12);
}

TEST(ParamLayout, IncrementClampsToBounds) {
  const RiggedModel m = test::make_toy_model();
  const ParamLayout layout(m);
  PoseParams p = PoseParams::identity(m);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(layout.num_params());
  d.segment<3>(layout.bone_offset(2) + 6) = Vec3(5.0, -5.0, 0.2);
  for (int k = 0; k < m.num_blendshapes(); ++k) d[layout.blendshape_offset(k)] = (k % 2 == 0) ? 10.0 : -10.0;
  layout.apply_increment(m, d, p);
  EXPECT_DOUBLE_EQ(p.bones[2].scale.x(), m.bones[2].scale_hi.x());
  EXPECT_DOUBLE_EQ(p.bones[2].scale.y(), m.bones[2].scale_lo.y());
  EXPECT_DOUBLE_EQ(p.bones[2].scale.z(), 1.2);
  for (int k = 0; k < m.num_blendshapes(); ++k)
    EXPECT_DOUBLE_EQ(p.alpha[k], (k % 2 == 0) ? m.blendshapes[k].hi : m.blendshapes[k].lo) << k;
}

TEST(ParamLayout, ClampToBoundsAndSizeChecks) {
  const RiggedModel m = test::make_toy_model();
  const ParamLayout layout(m);
  PoseParams p = PoseParams::identity(m);
  p.bones[0].scale = Vec3(0.01, 1.0, 100.0);
  p.alpha[1] = -3.0;
  layout.clamp_to_bounds(m, p);
  EXPECT_DOUBLE_EQ(p.bones[0].scale.x(), m.bones[0].scale_lo.x());
  EXPECT_DOUBLE_EQ(p.bones[0].scale.z(), m.bones[0].scale_hi.z());
  EXPECT_DOUBLE_EQ(p.alpha[1], m.blendshapes[1].lo);
  EXPECT_THROW(layout.apply_increment(m, Eigen::VectorXd::Zero(3), p), InvalidInput);
  p.alpha.resize(1);
  EXPECT_THROW(layout.clamp_to_bounds(m, p), InvalidInput);
}

}  // namespace
}  // namespace breastfit::model
