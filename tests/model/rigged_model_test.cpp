#include "breastfit/model/rigged_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "breastfit/core/errors.h"
#include "support/toy_model.h"

namespace breastfit::model {
namespace {

TEST(RiggedModel, ToyModelIsValidAndAsDescribed) {
  const RiggedModel m = test::make_toy_model();
  EXPECT_NO_THROW(m.validate());
  EXPECT_EQ(m.num_vertices(), 410);
  EXPECT_EQ(m.rest.num_faces(), 816);
  EXPECT_EQ(m.num_bones(), 4);
  EXPECT_EQ(m.num_blendshapes(), 6);
  EXPECT_EQ(m.landmarks.size(), 3u);
  EXPECT_EQ(m.drawings.size(), 2u);
  int max_influences = 0;
  for (Index i = 0; i < m.num_vertices(); ++i) {
    int n = 0;
    for (SkinWeights::InnerIterator it(m.weights, i); it; ++it) n += it.value() > 0;
    max_influences = std::max(max_influences, n);
  }
  EXPECT_EQ(max_influences, 3);
  // Some shapes are local, some global.
  EXPECT_GT(m.blendshapes[1].vertices.size(), 300u);
  EXPECT_LT(m.blendshapes[3].vertices.size(), 60u);
  EXPECT_GT(m.blendshapes[3].vertices.size(), 5u);
}

TEST(RiggedModel, NameLookups) {
  const RiggedModel m = test::make_toy_model();
  EXPECT_EQ(m.bone_index("chest"), 2);
  EXPECT_EQ(m.bone_index("femur"), std::nullopt);
  EXPECT_EQ(m.blendshape_index("breast_L"), 4);
  EXPECT_EQ(m.landmark_index("nipple_R"), 1);
  EXPECT_EQ(m.drawing_index("breast_contour_R"), 1);
  EXPECT_EQ(m.region_index("breast_R"), 0);
  EXPECT_EQ(m.region_index("breast_L"), std::nullopt);
}

// The vertices a bone mostly moves: exactly those whose weight on it is above the threshold, ascending.
TEST(RiggedModel, VerticesMostlyMovedByABone) {
  const RiggedModel m = test::make_toy_model();
  for (int bone = 0; bone < m.num_bones(); ++bone)
    for (const double min_weight : {0.6, 0.3}) {
      std::vector<Index> expected;
      for (Index i = 0; i < m.num_vertices(); ++i)
        if (m.weights.coeff(i, bone) > min_weight) expected.push_back(i);
      EXPECT_EQ(m.vertices_mostly_moved_by(bone, min_weight), expected) << "bone " << bone << " above " << min_weight;
    }
  const int chest = *m.bone_index("chest");
  EXPECT_FALSE(m.vertices_mostly_moved_by(chest).empty());
  EXPECT_LE(m.vertices_mostly_moved_by(chest).size(), m.vertices_mostly_moved_by(chest, 0.3).size());
}

void expect_invalid(const std::function<void(RiggedModel&)>& corrupt, const std::string& fragment) {
  RiggedModel m = test::make_toy_model();
  corrupt(m);
  try {
    m.validate();
    ADD_FAILURE() << "expected InvalidInput mentioning '" << fragment << "'";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(RiggedModel, ValidateNamesTheFirstViolation) {
  expect_invalid([](RiggedModel& m) { m.rest.F(3, 1) = 9999; }, "triangle 3");
  expect_invalid([](RiggedModel& m) { m.rest.V(0, 0) = std::nan(""); }, "non-finite vertex");
  expect_invalid([](RiggedModel& m) { m.bones[1].parent = 3; }, "bone 'spine'");
  expect_invalid([](RiggedModel& m) { m.bones[2].name = "pelvis"; }, "duplicate bone");
  expect_invalid([](RiggedModel& m) { m.bones[0].axes(0, 0) += 0.1; }, "orthonormal");
  expect_invalid([](RiggedModel& m) { m.bones[0].axes.col(0) *= -1; }, "right-handed");
  expect_invalid([](RiggedModel& m) { m.bones[3].scale_lo.x() = 0; }, "must be > 0");
  expect_invalid([](RiggedModel& m) { m.bones[3].scale_lo.y() = 3; }, "scale bounds");
  expect_invalid([](RiggedModel& m) { m.bones[3].scale_stiffness.z() = 0; }, "scale stiffness");
  expect_invalid([](RiggedModel& m) { m.bones[3].scale_stiffness.x() = std::nan(""); }, "scale stiffness");
  expect_invalid([](RiggedModel& m) { m.weights.coeffRef(5, m.weights.innerIndexPtr()[m.weights.outerIndexPtr()[5]]) += 0.1; },
                 "vertex 5");
  expect_invalid([](RiggedModel& m) { m.weights.conservativeResize(m.num_vertices(), 3); }, "skin weights");
  expect_invalid([](RiggedModel& m) { m.blendshapes[3].vertices[1] = m.blendshapes[3].vertices[0]; }, "ascending");
  expect_invalid([](RiggedModel& m) { m.blendshapes[3].displacements.conservativeResize(2, 3); }, "displacement rows");
  expect_invalid([](RiggedModel& m) { m.blendshapes[0].lo = 2; }, "blendshape 'bulge'");
  expect_invalid([](RiggedModel& m) { m.landmarks[0].point.face = -1; }, "landmark 'sternal_notch'");
  expect_invalid([](RiggedModel& m) { m.landmarks[1].point.bary = Vec3(0.5, 0.5, 0.5); }, "sum to 1");
  expect_invalid([](RiggedModel& m) { m.drawings[0].points[4].bary = Vec3(1.5, -0.5, 0); }, "drawing 'sternum' point 4");
  expect_invalid([](RiggedModel& m) { m.regions[0].vertices.push_back(410); }, "region 'breast_R'");
}

}  // namespace
}  // namespace breastfit::model
