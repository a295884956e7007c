// End-to-end tests of `breastfit template` through the built executable, on the toy model.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "breastfit/io/io.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/pose_evaluator.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path write_toy(const fs::path& dir) {
  const fs::path file = dir / "toy.glb";
  model::save_gltf(file, test::make_toy_model());
  return file;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

TEST(TemplateCommand, InfoText) {
  const fs::path file = write_toy(test::temp_dir());
  std::string out;
  ASSERT_EQ(test::run_cli("template info " + q(file), &out), 0) << out;
  for (const char* s : {"toy", "410 vertices", "816 faces", "pelvis", "chest", "breast_R", "[0, 1.5]",
                        "sternal_notch", "breast_contour_R", "closed", "sternum"})
    EXPECT_NE(out.find(s), std::string::npos) << "missing '" << s << "' in\n" << out;
}

TEST(TemplateCommand, InfoJson) {
  const fs::path file = write_toy(test::temp_dir());
  std::string out;
  ASSERT_EQ(test::run_cli("template info " + q(file) + " --json", &out), 0) << out;
  const json j = json::parse(out);
  EXPECT_EQ(j["num_vertices"], 410);
  EXPECT_EQ(j["num_faces"], 816);
  EXPECT_EQ(j["num_params"], 7 + 36 + 6);
  for (const char* key : {"bones", "blendshapes", "landmarks", "drawings"}) {
    ASSERT_TRUE(j[key].is_array()) << key;
    for (const auto& item : j[key]) EXPECT_TRUE(item["name"].is_string()) << key;
  }
  EXPECT_EQ(j["bones"].size(), 4u);
  EXPECT_EQ(j["bones"][1]["name"], "spine");
  EXPECT_EQ(j["bones"][1]["parent"], "pelvis");
  EXPECT_TRUE(j["bones"][0]["parent"].is_null());
  EXPECT_EQ(j["blendshapes"].size(), 6u);
  EXPECT_EQ(j["blendshapes"][2]["name"], "twist");
  EXPECT_EQ(j["blendshapes"][2]["lo"], -2.0);
  EXPECT_EQ(j["landmarks"].size(), 3u);
  EXPECT_EQ(j["drawings"][1]["closed"], true);
  EXPECT_EQ(j["num_landmarks"], 3);
  EXPECT_EQ(j["num_drawings"], 2);
}

TEST(TemplateCommand, InfoUsesDefaultTemplateFromEnvironment) {
  const fs::path file = write_toy(test::temp_dir());
  ::setenv("BREASTFIT_TEMPLATE", file.c_str(), 1);
  std::string out;
  const int code = test::run_cli("template info --json", &out);
  ::setenv("BREASTFIT_TEMPLATE", (file.parent_path() / "missing.glb").c_str(), 1);
  std::string err;
  const int missing_code = test::run_cli("template info", &err);
  ::unsetenv("BREASTFIT_TEMPLATE");
  ASSERT_EQ(code, 0) << out;
  EXPECT_EQ(json::parse(out)["name"], "toy");
  EXPECT_EQ(missing_code, 4) << err;
  EXPECT_NE(err.find("missing.glb"), std::string::npos) << err;
}

TEST(TemplateCommand, InfoMissingFileIsIoError) {
  std::string out;
  EXPECT_EQ(test::run_cli("template info " + q(test::temp_dir() / "none.glb"), &out), 4) << out;
  EXPECT_NE(out.find("breastfit: error:"), std::string::npos) << out;
}

TEST(TemplateCommand, PoseWritesPosedMesh) {
  const fs::path dir = test::temp_dir();
  const fs::path file = write_toy(dir);
  std::ofstream(dir / "p.json") << R"({"global.translation.x": 10, "bone.chest.rotation.x": 0.2,
                                       "bone.spine.scale.z": 1.3, "shape.breast_R": 0.8})";
  std::string out;
  ASSERT_EQ(test::run_cli("template pose --template " + q(file) + " --params " + q(dir / "p.json") + " --out " +
                              q(dir / "posed.ply"),
                          &out),
            0)
      << out;
  const TriangleMesh posed = io::read_mesh(dir / "posed.ply");
  const model::RiggedModel toy = test::make_toy_model();
  model::PoseParams p = model::PoseParams::identity(toy);
  p.global.translation.x() = 10;
  p.bones[2].rotation = Quat(Eigen::AngleAxisd(0.2, Vec3::UnitX()));
  p.bones[1].scale.z() = 1.3;
  p.alpha[3] = 0.8;
  const Points expected = model::pose_vertices(toy, p);
  ASSERT_EQ(posed.num_vertices(), toy.num_vertices());
  EXPECT_EQ(posed.F, toy.rest.F);
  EXPECT_LT((posed.V - expected).cwiseAbs().maxCoeff(), 1e-3);  // float32 PLY
  EXPECT_GT((posed.V - toy.rest.V).cwiseAbs().maxCoeff(), 10.0 - 1e-6);
}

TEST(TemplateCommand, PoseAppliesTheSurfaceDetailOfARegisterParamsFile) {
  const fs::path dir = test::temp_dir();
  const fs::path file = write_toy(dir);
  const model::RiggedModel toy = test::make_toy_model();
  // As register writes it: the parameters under "params", the detail's offsets (here 3 mm on
  // every vertex) beside them.
  json p = {{"params", {{"global.translation.x", 10}}},
            {"surface_detail", {{"offsets_mm", std::vector<double>(static_cast<size_t>(toy.num_vertices()), 3.0)}}}};
  std::ofstream(dir / "p.json") << p.dump();
  std::string out;
  const std::string cmd = "template pose --template " + q(file) + " --params " + q(dir / "p.json") + " --out ";
  ASSERT_EQ(test::run_cli(cmd + q(dir / "detail.ply"), &out), 0) << out;
  EXPECT_NE(out.find("surface detail applied"), std::string::npos) << out;
  ASSERT_EQ(test::run_cli(cmd + q(dir / "alone.ply") + " --no-detail", &out), 0) << out;
  EXPECT_NE(out.find("NOT applied"), std::string::npos) << out;
  const TriangleMesh detail = io::read_mesh(dir / "detail.ply"), alone = io::read_mesh(dir / "alone.ply");
  const Points moved = detail.V - alone.V;
  EXPECT_NEAR(moved.rowwise().norm().minCoeff(), 3.0, 1e-3);
  EXPECT_NEAR(moved.rowwise().norm().maxCoeff(), 3.0, 1e-3);

  // Offsets of another template: refused, naming the counts.
  p["surface_detail"]["offsets_mm"] = {1.0, 2.0};
  std::ofstream(dir / "p.json") << p.dump();
  EXPECT_EQ(test::run_cli(cmd + q(dir / "bad.ply"), &out), 3) << out;
  EXPECT_NE(out.find("has 2 offsets"), std::string::npos) << out;
  // Parameters without detail: said so.
  std::ofstream(dir / "p.json") << R"({"params": {"global.translation.x": 10}})";
  ASSERT_EQ(test::run_cli(cmd + q(dir / "plain.ply"), &out), 0) << out;
  EXPECT_NE(out.find("no surface detail"), std::string::npos) << out;
}

TEST(TemplateCommand, PoseRejectsUnknownParameter) {
  const fs::path dir = test::temp_dir();
  const fs::path file = write_toy(dir);
  std::ofstream(dir / "p.json") << R"({"params": {"bone.femur.rotation.x": 0.1}})";
  std::string out;
  EXPECT_EQ(test::run_cli("template pose --template " + q(file) + " --params " + q(dir / "p.json") + " --out " +
                              q(dir / "posed.ply"),
                          &out),
            3)
      << out;
  EXPECT_NE(out.find("bone.femur.rotation.x"), std::string::npos) << out;
  EXPECT_NE(out.find("global.rotation.x"), std::string::npos) << out;
  EXPECT_FALSE(fs::exists(dir / "posed.ply"));
}

TEST(TemplateCommand, BuildWritesLoadableDefaultTemplate) {
  const fs::path dir = test::temp_dir();
  std::string out;
  ASSERT_EQ(test::run_cli("template build --out " + q(dir / "default.glb"), &out), 0) << out;
  const model::RiggedModel m = model::load_gltf(dir / "default.glb");
  EXPECT_GT(m.num_vertices(), 1000);
  EXPECT_EQ(m.num_bones(), 9);
  EXPECT_GE(m.num_blendshapes(), 20);
  EXPECT_EQ(m.landmarks.size(), 12u);
  EXPECT_FALSE(m.drawings.empty());
  EXPECT_EQ(test::run_cli("template build", &out), 2) << "--out is required";
}

}  // namespace
}  // namespace breastfit
