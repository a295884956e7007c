// The shipped assets/templates/default_torso.glb is what build_default_template() makes.
#include <gtest/gtest.h>

#include <filesystem>

#include "breastfit/model/gltf_io.h"
#include "breastfit/template/default_template.h"
#include "support/test_paths.h"

namespace breastfit::templ {
namespace {

TEST(TemplateAsset, ShippedGlbMatchesTheBuilder) {
  const auto path = test::source_dir() / "assets" / "templates" / "default_torso.glb";
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  const model::RiggedModel shipped = model::load_gltf(path);
  const model::RiggedModel built = build_default_template();
  EXPECT_NO_THROW(shipped.validate());

  // Mesh: same topology, positions within float32 precision (the file stores metres in float32).
  ASSERT_EQ(shipped.num_vertices(), built.num_vertices());
  ASSERT_EQ(shipped.rest.num_faces(), built.rest.num_faces());
  EXPECT_TRUE(shipped.rest.F == built.rest.F);
  EXPECT_LT((shipped.rest.V - built.rest.V).cwiseAbs().maxCoeff(), 1e-4);

  // Bones.
  ASSERT_EQ(shipped.num_bones(), built.num_bones());
  for (int j = 0; j < built.num_bones(); ++j) {
    EXPECT_EQ(shipped.bones[j].name, built.bones[j].name);
    EXPECT_EQ(shipped.bones[j].parent, built.bones[j].parent);
    EXPECT_LT((shipped.bones[j].pivot - built.bones[j].pivot).norm(), 1e-6);
    EXPECT_LT((shipped.bones[j].axes - built.bones[j].axes).norm(), 1e-6);
  }
  EXPECT_LT((Eigen::MatrixXd(shipped.weights) - Eigen::MatrixXd(built.weights)).cwiseAbs().maxCoeff(), 1e-6);

  // Blendshapes: names, bounds, displacements (float32).
  ASSERT_EQ(shipped.num_blendshapes(), built.num_blendshapes());
  for (int k = 0; k < built.num_blendshapes(); ++k) {
    const auto& a = shipped.blendshapes[k];
    const auto& b = built.blendshapes[k];
    EXPECT_EQ(a.name, b.name);
    EXPECT_DOUBLE_EQ(a.lo, b.lo);
    EXPECT_DOUBLE_EQ(a.hi, b.hi);
    Points da = Points::Zero(built.num_vertices(), 3), db = da;
    for (size_t i = 0; i < a.vertices.size(); ++i) da.row(a.vertices[i]) = a.displacements.row(static_cast<Index>(i));
    for (size_t i = 0; i < b.vertices.size(); ++i) db.row(b.vertices[i]) = b.displacements.row(static_cast<Index>(i));
    EXPECT_LT((da - db).cwiseAbs().maxCoeff(), 1e-4) << b.name;
  }

  // Landmarks, drawings, regions.
  ASSERT_EQ(shipped.landmarks.size(), built.landmarks.size());
  for (size_t i = 0; i < built.landmarks.size(); ++i) {
    EXPECT_EQ(shipped.landmarks[i].name, built.landmarks[i].name);
    EXPECT_EQ(shipped.landmarks[i].point.face, built.landmarks[i].point.face);
    EXPECT_LT((shipped.landmarks[i].point.bary - built.landmarks[i].point.bary).norm(), 1e-9);
  }
  ASSERT_EQ(shipped.drawings.size(), built.drawings.size());
  for (size_t i = 0; i < built.drawings.size(); ++i) {
    EXPECT_EQ(shipped.drawings[i].name, built.drawings[i].name);
    EXPECT_EQ(shipped.drawings[i].closed, built.drawings[i].closed);
    ASSERT_EQ(shipped.drawings[i].points.size(), built.drawings[i].points.size());
    for (size_t k = 0; k < built.drawings[i].points.size(); ++k)
      EXPECT_EQ(shipped.drawings[i].points[k].face, built.drawings[i].points[k].face);
  }
  ASSERT_EQ(shipped.regions.size(), built.regions.size());
  for (size_t i = 0; i < built.regions.size(); ++i) {
    EXPECT_EQ(shipped.regions[i].name, built.regions[i].name);
    EXPECT_EQ(shipped.regions[i].vertices, built.regions[i].vertices);
  }
}

}  // namespace
}  // namespace breastfit::templ
