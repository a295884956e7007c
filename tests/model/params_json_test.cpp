#include "breastfit/model/params_json.h"

#include <gtest/gtest.h>

#include <fstream>

#include "breastfit/core/errors.h"
#include "breastfit/model/param_layout.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit::model {
namespace {

using json = nlohmann::json;

void expect_same_params(const PoseParams& a, const PoseParams& b, double tol) {
  EXPECT_LT(a.global.rotation.angularDistance(b.global.rotation), tol);
  EXPECT_LT((a.global.translation - b.global.translation).norm(), tol);
  EXPECT_NEAR(a.global.scale, b.global.scale, tol);
  ASSERT_EQ(a.bones.size(), b.bones.size());
  for (size_t j = 0; j < a.bones.size(); ++j) {
    EXPECT_LT(a.bones[j].rotation.angularDistance(b.bones[j].rotation), tol) << j;
    EXPECT_LT((a.bones[j].translation - b.bones[j].translation).norm(), tol) << j;
    EXPECT_LT((a.bones[j].scale - b.bones[j].scale).norm(), tol) << j;
  }
  EXPECT_LT((a.alpha - b.alpha).norm(), tol);
}

TEST(ParamsJson, RoundTripsEveryParameter) {
  const RiggedModel m = test::make_toy_model();
  const PoseParams p = test::random_toy_pose(m, 17);
  const json doc = params_to_json(m, p);
  EXPECT_EQ(doc["format"], "breastfit.params");
  const ParamLayout layout(m);
  EXPECT_EQ(doc["params"].size(), static_cast<size_t>(layout.num_params()));
  for (int q = 0; q < layout.num_params(); ++q) EXPECT_TRUE(doc["params"].contains(layout.name(q))) << layout.name(q);
  EXPECT_DOUBLE_EQ(doc["params"]["global.scale"].get<double>(), p.global.scale);
  EXPECT_DOUBLE_EQ(doc["params"]["shape.dent"].get<double>(), p.alpha[5]);
  expect_same_params(params_from_json(m, doc), p, 1e-12);
  // Through text and a file, with extra metadata next to "params".
  json with_meta = doc;
  with_meta["units_note"] = "mm";
  const auto file = test::temp_dir() / "params.json";
  write_params_json(file, m, p);
  expect_same_params(read_params_json(file, m), p, 1e-12);
  expect_same_params(params_from_json(m, json::parse(with_meta.dump())), p, 1e-12);
}

TEST(ParamsJson, SubsetKeepsTheRestFromBase) {
  const RiggedModel m = test::make_toy_model();
  const json flat = {{"global.translation.y", 12.5},
                     {"global.scale", 1.2},
                     {"bone.chest.rotation.z", 0.3},
                     {"bone.spine.scale.x", 1.25},
                     {"shape.breast_R", 0.75}};
  const PoseParams p = params_from_json(m, flat);
  EXPECT_TRUE(p.global.translation.isApprox(Vec3(0, 12.5, 0)));
  EXPECT_DOUBLE_EQ(p.global.scale, 1.2);
  EXPECT_LT(p.bones[2].rotation.angularDistance(Quat(Eigen::AngleAxisd(0.3, Vec3::UnitZ()))), 1e-14);
  EXPECT_TRUE(p.bones[1].scale.isApprox(Vec3(1.25, 1, 1)));
  EXPECT_DOUBLE_EQ(p.alpha[3], 0.75);
  EXPECT_DOUBLE_EQ(p.alpha[0], 0.0);
  EXPECT_LT(p.bones[0].rotation.angularDistance(Quat::Identity()), 1e-15);

  // A partial rotation keeps the base's other rotation-vector components.
  PoseParams base = PoseParams::identity(m);
  base.bones[0].rotation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX()));
  base.alpha[1] = 0.5;
  const PoseParams q = params_from_json(m, json{{"bone.pelvis.rotation.y", 0.1}}, base);
  const Vec3 rv(0.2, 0.1, 0.0);
  EXPECT_LT(q.bones[0].rotation.angularDistance(Quat(Eigen::AngleAxisd(rv.norm(), rv.normalized()))), 1e-14);
  EXPECT_DOUBLE_EQ(q.alpha[1], 0.5);
}

TEST(ParamsJson, RejectsBadNamesAndValues) {
  const RiggedModel m = test::make_toy_model();
  try {
    params_from_json(m, json{{"bone.femur.scale.x", 1.0}});
    ADD_FAILURE() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bone.femur.scale.x"), std::string::npos) << what;
    EXPECT_NE(what.find("global.rotation.x"), std::string::npos) << what;
    EXPECT_NE(what.find("bone.pelvis.rotation.x"), std::string::npos) << what;
    EXPECT_NE(what.find("shape.bulge"), std::string::npos) << what;
  }
  EXPECT_THROW(params_from_json(m, json{{"shape.bulge", "a lot"}}), InvalidInput);
  EXPECT_THROW(params_from_json(m, json{{"shape.bulge", 3.0}}), InvalidInput);        // bounds [-1, 1]
  EXPECT_THROW(params_from_json(m, json{{"bone.neck.scale.y", 0.1}}), InvalidInput);  // bounds [0.8, 1.3]
  EXPECT_THROW(params_from_json(m, json{{"global.scale", 0.0}}), InvalidInput);
  EXPECT_THROW(params_from_json(m, json::array({1, 2})), InvalidInput);
  EXPECT_THROW(params_from_json(m, json{{"params", 3}}), InvalidInput);
  const auto dir = test::temp_dir();
  EXPECT_THROW(read_params_json(dir / "missing.json", m), IoError);
  std::ofstream(dir / "bad.json") << "{ not json";
  EXPECT_THROW(read_params_json(dir / "bad.json", m), IoError);
}

}  // namespace
}  // namespace breastfit::model
