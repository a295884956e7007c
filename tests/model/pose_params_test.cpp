#include "breastfit/model/pose_params.h"

#include <gtest/gtest.h>

#include <vector>

#include "breastfit/model/rigged_model.h"
#include "support/toy_model.h"

namespace breastfit::model {
namespace {

Similarity sample_similarity() {
  Similarity s;
  s.rotation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()));
  s.translation = Vec3(10, -4, 33);
  s.scale = 1.7;
  return s;
}

TEST(Similarity, InverseUndoesApply) {
  const Similarity s = sample_similarity();
  const Similarity inv = s.inverse();
  for (const Vec3& x : std::vector<Vec3>{Vec3(1, 2, 3), Vec3(-40, 0, 7), Vec3(0, 0, 0)}) {
    EXPECT_LT((inv.apply(s.apply(x)) - x).norm(), 1e-12);
    EXPECT_LT((s.apply(inv.apply(x)) - x).norm(), 1e-12);
  }
  EXPECT_NEAR(inv.scale, 1.0 / 1.7, 1e-15);
}

TEST(Similarity, ComposeAppliesOtherFirst) {
  const Similarity a = sample_similarity();
  Similarity b;
  b.rotation = Quat(Eigen::AngleAxisd(-0.3, Vec3::UnitZ()));
  b.translation = Vec3(0, 5, -1);
  b.scale = 0.8;
  const Similarity ab = a.compose(b);
  const Vec3 x(3, -7, 2);
  EXPECT_LT((ab.apply(x) - a.apply(b.apply(x))).norm(), 1e-12);
  EXPECT_NEAR(ab.scale, 1.7 * 0.8, 1e-15);
  const Similarity id = a.compose(a.inverse());
  EXPECT_LT((id.apply(x) - x).norm(), 1e-12);
}

TEST(PoseParams, IdentityMatchesModel) {
  const RiggedModel m = test::make_toy_model();
  const PoseParams p = PoseParams::identity(m);
  ASSERT_EQ(p.bones.size(), m.bones.size());
  EXPECT_EQ(p.alpha.size(), m.num_blendshapes());
  EXPECT_TRUE(p.alpha.isZero());
  for (const auto& b : p.bones) {
    EXPECT_TRUE(b.scale.isApprox(Vec3::Ones()));
    EXPECT_TRUE(b.translation.isZero());
    EXPECT_NEAR(b.rotation.angularDistance(Quat::Identity()), 0.0, 1e-15);
  }
  EXPECT_DOUBLE_EQ(p.global.scale, 1.0);
}

}  // namespace
}  // namespace breastfit::model
