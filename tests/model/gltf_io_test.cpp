#include "breastfit/model/gltf_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/model/pose_evaluator.h"
#include "support/test_paths.h"
#include "support/toy_model.h"

namespace breastfit::model {
namespace {

void expect_same_model(const RiggedModel& a, const RiggedModel& b) {
  EXPECT_EQ(a.name, b.name);
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.rest.num_faces(), b.rest.num_faces());
  EXPECT_EQ(a.rest.F, b.rest.F);
  // float32 vertex data: relative precision ~6e-8 of |x| ≤ 240 mm.
  EXPECT_LT((a.rest.V - b.rest.V).cwiseAbs().maxCoeff(), 1e-4);
  ASSERT_EQ(a.num_bones(), b.num_bones());
  for (int j = 0; j < a.num_bones(); ++j) {
    SCOPED_TRACE(a.bones[j].name);
    EXPECT_EQ(a.bones[j].name, b.bones[j].name);
    EXPECT_EQ(a.bones[j].parent, b.bones[j].parent);
    EXPECT_EQ(a.bones[j].pivot, b.bones[j].pivot);  // exact: stored as doubles in extras
    EXPECT_EQ(a.bones[j].axes, b.bones[j].axes);
    EXPECT_EQ(a.bones[j].scale_lo, b.bones[j].scale_lo);
    EXPECT_EQ(a.bones[j].scale_hi, b.bones[j].scale_hi);
    EXPECT_EQ(a.bones[j].scale_stiffness, b.bones[j].scale_stiffness);
  }
  EXPECT_LT((Eigen::MatrixXd(a.weights) - Eigen::MatrixXd(b.weights)).cwiseAbs().maxCoeff(), 1e-6);
  ASSERT_EQ(a.num_blendshapes(), b.num_blendshapes());
  for (int k = 0; k < a.num_blendshapes(); ++k) {
    SCOPED_TRACE(a.blendshapes[k].name);
    EXPECT_EQ(a.blendshapes[k].name, b.blendshapes[k].name);
    EXPECT_EQ(a.blendshapes[k].lo, b.blendshapes[k].lo);
    EXPECT_EQ(a.blendshapes[k].hi, b.blendshapes[k].hi);
    EXPECT_EQ(a.blendshapes[k].vertices, b.blendshapes[k].vertices);
    if (a.blendshapes[k].vertices == b.blendshapes[k].vertices)
      EXPECT_LT((a.blendshapes[k].displacements - b.blendshapes[k].displacements).cwiseAbs().maxCoeff(), 1e-5);
  }
  ASSERT_EQ(a.landmarks.size(), b.landmarks.size());
  for (size_t l = 0; l < a.landmarks.size(); ++l) {
    EXPECT_EQ(a.landmarks[l].name, b.landmarks[l].name);
    EXPECT_EQ(a.landmarks[l].point.face, b.landmarks[l].point.face);
    EXPECT_EQ(a.landmarks[l].point.bary, b.landmarks[l].point.bary);
  }
  ASSERT_EQ(a.drawings.size(), b.drawings.size());
  for (size_t d = 0; d < a.drawings.size(); ++d) {
    EXPECT_EQ(a.drawings[d].name, b.drawings[d].name);
    EXPECT_EQ(a.drawings[d].closed, b.drawings[d].closed);
    ASSERT_EQ(a.drawings[d].points.size(), b.drawings[d].points.size());
    for (size_t p = 0; p < a.drawings[d].points.size(); ++p) {
      EXPECT_EQ(a.drawings[d].points[p].face, b.drawings[d].points[p].face);
      EXPECT_EQ(a.drawings[d].points[p].bary, b.drawings[d].points[p].bary);
    }
  }
  ASSERT_EQ(a.regions.size(), b.regions.size());
  for (size_t r = 0; r < a.regions.size(); ++r) {
    EXPECT_EQ(a.regions[r].name, b.regions[r].name);
    EXPECT_EQ(a.regions[r].vertices, b.regions[r].vertices);
  }
}

TEST(GltfIo, ToyModelRoundTripsThroughGltfAndGlb) {
  RiggedModel toy = test::make_toy_model();
  toy.bones[1].scale_stiffness = Vec3(1.0, 5.0, 2.5);  // non-default: must survive the round trip
  const auto dir = test::temp_dir();
  for (const char* file : {"toy.gltf", "toy.glb", "TOY.GLB"}) {
    SCOPED_TRACE(file);
    save_gltf(dir / file, toy);
    const RiggedModel back = load_gltf(dir / file);
    expect_same_model(toy, back);
    // Posing the loaded model gives the same mesh.
    const PoseParams p = test::random_toy_pose(toy, 5);
    EXPECT_LT((pose_vertices(toy, p) - pose_vertices(back, p)).cwiseAbs().maxCoeff(), 1e-3);
  }
  // .gltf embeds the buffer as base64 and keeps Blender-readable names.
  std::ifstream in(dir / "toy.gltf");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["buffers"][0]["uri"].get<std::string>().rfind("data:application/octet-stream;base64,", 0), 0u);
  EXPECT_EQ(j["meshes"][0]["extras"]["targetNames"].size(), 6u);
  EXPECT_EQ(j["meshes"][0]["extras"]["targetNames"][3], "breast_R");
  EXPECT_TRUE(j["accessors"][j["meshes"][0]["primitives"][0]["targets"][3]["POSITION"].get<int>()].contains("sparse"));
  // glTF frame: metres, +Y up. The toy's top (z = 240 mm) is at y = 0.24 m.
  const auto& pos = j["accessors"][j["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
  EXPECT_NEAR(pos["max"][1].get<double>(), 0.24, 1e-6);
  EXPECT_NEAR(pos["max"][0].get<double>(), 0.06, 1e-6);
}

TEST(GltfIo, MoreThanFourInfluencesUseJoints1) {
  RiggedModel m = test::make_toy_model();
  for (int extra = 0; extra < 3; ++extra) {
    Bone b;
    b.name = "extra" + std::to_string(extra);
    b.parent = 3;
    b.pivot = Vec3(10.0 * extra, 0, 230);
    m.bones.push_back(b);
  }
  std::vector<Eigen::Triplet<double, Index>> t;
  for (Index i = 0; i < m.num_vertices(); ++i) {
    if (i == 7) {
      for (int j = 0; j < 7; ++j) t.emplace_back(i, j, (j + 1) / 28.0);
    } else {
      for (SkinWeights::InnerIterator it(m.weights, i); it; ++it) t.emplace_back(i, static_cast<Index>(it.col()), it.value());
    }
  }
  m.weights.resize(m.num_vertices(), 7);
  m.weights.setFromTriplets(t.begin(), t.end());
  ASSERT_NO_THROW(m.validate());
  const auto file = test::temp_dir() / "seven.glb";
  save_gltf(file, m);
  const RiggedModel back = load_gltf(file);
  expect_same_model(m, back);
  EXPECT_NEAR(back.weights.coeff(7, 6), 7 / 28.0, 1e-7);

  // Nine influences cannot be written.
  m.bones.push_back(Bone{"extra3", 3, Vec3(0, 0, 235)});
  m.bones.push_back(Bone{"extra4", 3, Vec3(0, 0, 236)});
  t.clear();
  for (Index i = 0; i < m.num_vertices(); ++i)
    for (int j = 0; j < 9; ++j) t.emplace_back(i, j, 1.0 / 9);
  m.weights.resize(m.num_vertices(), 9);
  m.weights.setFromTriplets(t.begin(), t.end());
  EXPECT_THROW(save_gltf(file, m), InvalidInput);
}

TEST(GltfIo, LoadsBlenderStyleRig) {
  const RiggedModel m = load_gltf(test::data_dir() / "gltf" / "blender_box.gltf");
  EXPECT_EQ(m.name, "Body");
  EXPECT_EQ(m.num_vertices(), 8) << "the UV-seam copy is welded";
  EXPECT_EQ(m.rest.num_faces(), 12);
  // Frame: glTF (x, y, z) m -> LPS (1000x, -1000z, 1000y) mm.
  EXPECT_TRUE(m.rest.V.row(0).isApprox(Eigen::RowVector3d(-100, 50, 0), 1e-6));
  EXPECT_TRUE(m.rest.V.row(6).isApprox(Eigen::RowVector3d(100, -50, 400), 1e-6));
  ASSERT_EQ(m.num_bones(), 2);
  EXPECT_EQ(m.bones[0].name, "Spine");
  EXPECT_EQ(m.bones[1].name, "Chest");
  EXPECT_EQ(m.bones[0].parent, std::nullopt);
  EXPECT_EQ(m.bones[1].parent, 0);
  const double a = 10.0 * std::numbers::pi / 180;
  EXPECT_LT(m.bones[0].pivot.norm(), 1e-9);
  EXPECT_LT((m.bones[1].pivot - Vec3(-200 * std::sin(a), 0, 200 * std::cos(a))).norm(), 1e-9);
  EXPECT_TRUE(m.bones[1].axes.isIdentity());
  EXPECT_TRUE(m.bones[1].scale_lo.isApprox(Vec3::Constant(0.5)));
  // Weights: bottom all Spine; vertex 5 had (0.25, 0.7) and is renormalised.
  EXPECT_DOUBLE_EQ(m.weights.coeff(0, 0), 1.0);
  EXPECT_NEAR(m.weights.coeff(4, 1), 0.7, 1e-7);
  EXPECT_NEAR(m.weights.coeff(5, 0), 0.25 / 0.95, 1e-7);
  EXPECT_NEAR(m.weights.coeff(5, 1), 0.7 / 0.95, 1e-7);
  ASSERT_EQ(m.num_blendshapes(), 2);
  EXPECT_EQ(m.blendshapes[0].name, "Key 1");
  EXPECT_EQ(m.blendshapes[1].name, "Breast");
  for (const auto& s : m.blendshapes) {
    EXPECT_EQ(s.lo, 0.0);
    EXPECT_EQ(s.hi, 1.0);
  }
  EXPECT_EQ(m.blendshapes[0].vertices, (std::vector<Index>{4, 5, 6, 7}));
  ASSERT_EQ(m.blendshapes[1].vertices, (std::vector<Index>{6}));  // sparse target; copy 8 welded into 6
  EXPECT_TRUE(m.blendshapes[1].displacements.row(0).isApprox(Eigen::RowVector3d(0, -50, 0), 1e-6));  // forward = −P
  EXPECT_TRUE(m.landmarks.empty());
  EXPECT_NO_THROW(m.validate());
  // Rest pose of the loaded rig reproduces the rest mesh, and it can be re-saved and re-loaded.
  EXPECT_LT((pose_vertices(m, PoseParams::identity(m)) - m.rest.V).cwiseAbs().maxCoeff(), 1e-9);
  const auto file = test::temp_dir() / "box.glb";
  save_gltf(file, m);
  expect_same_model(m, load_gltf(file));
}

TEST(GltfIo, MeshWithoutSkinGetsOneRootBone) {
  const auto dir = test::temp_dir();
  save_gltf(dir / "toy.gltf", test::make_toy_model());
  std::ifstream in(dir / "toy.gltf");
  auto j = nlohmann::json::parse(in);
  j.erase("skins");
  j["nodes"][0].erase("skin");
  auto& attrs = j["meshes"][0]["primitives"][0]["attributes"];
  attrs.erase("JOINTS_0");
  attrs.erase("WEIGHTS_0");
  j["meshes"][0]["extras"].erase("breastfit");
  j["nodes"][0]["translation"] = {0.0, 0.0, 0.001};  // the mesh node transform applies without a skin
  std::ofstream(dir / "plain.gltf") << j.dump();
  const RiggedModel m = load_gltf(dir / "plain.gltf");
  ASSERT_EQ(m.num_bones(), 1);
  EXPECT_EQ(m.bones[0].name, "root");
  EXPECT_EQ(m.num_blendshapes(), 6);
  EXPECT_EQ(m.blendshapes[0].lo, 0.0);  // default bounds without extras
  const RiggedModel toy = test::make_toy_model();
  EXPECT_EQ(m.num_vertices(), toy.num_vertices());
  EXPECT_LT((m.rest.V.col(1) - (toy.rest.V.col(1).array() - 1.0).matrix()).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_LT((m.bones[0].pivot - m.rest.V.colwise().mean().transpose()).norm(), 1e-9);
}

/// A glTF with no skin whose one primitive draws the 4 vertices of a unit square (in metres) in
/// the given mode without an index accessor; the buffer is an embedded base64 data URI.
std::string square_gltf(int mode) {
  const float xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  std::string bytes(reinterpret_cast<const char*>(xyz), sizeof(xyz));
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string b64;
  for (size_t i = 0; i < bytes.size(); i += 3) {  // 48 bytes: no padding needed
    const auto a = static_cast<unsigned char>(bytes[i]), b = static_cast<unsigned char>(bytes[i + 1]),
               c = static_cast<unsigned char>(bytes[i + 2]);
    const unsigned v = (a << 16) | (b << 8) | c;
    for (int k = 3; k >= 0; --k) b64 += digits[(v >> (6 * k)) & 63];
  }
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"mode", mode}}}}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}, {"min", {0, 0, 0}},
         {"max", {1, 1, 0}}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", 48}}}},
      {"buffers", {{{"byteLength", 48}, {"uri", "data:application/octet-stream;base64," + b64}}}}};
  return j.dump();
}

TEST(GltfIo, TriangleStripAndFanPrimitivesAreTriangulated) {
  const auto dir = test::temp_dir();
  std::ofstream(dir / "strip.gltf") << square_gltf(5);
  const RiggedModel strip = load_gltf(dir / "strip.gltf");
  ASSERT_EQ(strip.rest.num_faces(), 2);
  EXPECT_EQ(strip.rest.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(strip.rest.F.row(1), (Eigen::RowVector3i(2, 1, 3)));
  std::ofstream(dir / "fan.gltf") << square_gltf(6);
  const RiggedModel fan = load_gltf(dir / "fan.gltf");
  ASSERT_EQ(fan.rest.num_faces(), 2);
  EXPECT_EQ(fan.rest.F.row(0), (Eigen::RowVector3i(0, 1, 2)));
  EXPECT_EQ(fan.rest.F.row(1), (Eigen::RowVector3i(0, 2, 3)));
}

TEST(GltfIo, BadFilesRaiseIoError) {
  const auto dir = test::temp_dir();
  EXPECT_THROW(load_gltf(dir / "missing.glb"), IoError);
  EXPECT_THROW(load_gltf(dir), IoError);
  std::ofstream(dir / "model.obj") << "v 0 0 0\n";
  EXPECT_THROW(load_gltf(dir / "model.obj"), IoError);
  std::ofstream(dir / "garbage.gltf") << "{ this is not json";
  EXPECT_THROW(load_gltf(dir / "garbage.gltf"), IoError);
  std::ofstream(dir / "garbage.glb") << "glTF\x02\x00\x00\x00 truncated";
  EXPECT_THROW(load_gltf(dir / "garbage.glb"), IoError);
  std::ofstream(dir / "empty.gltf") << R"({"asset": {"version": "2.0"}})";
  try {
    load_gltf(dir / "empty.gltf");
    ADD_FAILURE() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("no node with a mesh"), std::string::npos) << e.what();
  }

  // An index out of range and bad extras are reported with the file name.
  save_gltf(dir / "toy.gltf", test::make_toy_model());
  std::ifstream in(dir / "toy.gltf");
  const auto good = nlohmann::json::parse(in);
  auto j = good;
  j["meshes"][0]["extras"]["breastfit"]["landmarks"][0]["face"] = 100000;
  std::ofstream(dir / "bad_landmark.gltf") << j.dump();
  try {
    load_gltf(dir / "bad_landmark.gltf");
    ADD_FAILURE() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad_landmark.gltf"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("landmark 'sternal_notch'"), std::string::npos) << e.what();
  }
  j = good;
  j["meshes"][0]["extras"]["breastfit"]["drawings"][0]["closed"] = "yes";
  std::ofstream(dir / "bad_closed.gltf") << j.dump();
  EXPECT_THROW(load_gltf(dir / "bad_closed.gltf"), IoError);
  j = good;
  j["nodes"][2]["extras"]["breastfit"]["axes"] = {1, 2};
  std::ofstream(dir / "bad_axes.gltf") << j.dump();
  EXPECT_THROW(load_gltf(dir / "bad_axes.gltf"), IoError);
  j = good;
  j["accessors"][j["meshes"][0]["primitives"][0]["indices"].get<int>()]["count"] = 1000000 * 3;
  std::ofstream(dir / "bad_count.gltf") << j.dump();
  EXPECT_THROW(load_gltf(dir / "bad_count.gltf"), IoError);

  EXPECT_THROW(save_gltf(dir / "toy.obj", test::make_toy_model()), IoError);
  RiggedModel invalid = test::make_toy_model();
  invalid.blendshapes[0].lo = 5;
  EXPECT_THROW(save_gltf(dir / "invalid.glb", invalid), InvalidInput);
}

std::string load_problem(const std::filesystem::path& path, const std::string& mesh = "") {
  try {
    load_gltf(path, mesh);
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    return e.problem();
  }
  ADD_FAILURE() << "expected IoError for " << path;
  return "";
}

TEST(GltfIo, Gltf1EmptySkinAndSeveralSkinnedMeshesAreNamed) {
  const auto dir = test::temp_dir();
  std::ofstream(dir / "v1.gltf") << R"({"asset": {"version": "1.0"}, "scene": "s", "scenes": {"s": {"nodes": []}}})";
  EXPECT_EQ(load_problem(dir / "v1.gltf"), "glTF 1.0 is not supported (2.0 required): re-export the file as glTF 2.0");
  std::ofstream(dir / "v1.glb", std::ios::binary) << std::string("glTF\x01\x00\x00\x00\x14\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00", 20);
  EXPECT_NE(load_problem(dir / "v1.glb").find("glTF 1.0 is not supported"), std::string::npos);

  save_gltf(dir / "toy.gltf", test::make_toy_model());
  std::ifstream in(dir / "toy.gltf");
  const auto good = nlohmann::json::parse(in);
  auto j = good;
  j["skins"][0] = nlohmann::json::object();
  std::ofstream(dir / "empty_skin.gltf") << j.dump();
  EXPECT_EQ(load_problem(dir / "empty_skin.gltf"), "skin 0 has no joints (a skin needs a non-empty \"joints\" list)");

  j = good;
  auto second = j["nodes"][0];
  second["name"] = "Second";
  j["nodes"][0]["name"] = "First";
  j["nodes"].push_back(second);
  j["scenes"][0]["nodes"].push_back(j["nodes"].size() - 1);
  std::ofstream(dir / "two.gltf") << j.dump();
  EXPECT_EQ(load_problem(dir / "two.gltf"), "2 skinned meshes ('First', 'Second'): choose one with --mesh NAME");
  EXPECT_EQ(load_problem(dir / "two.gltf", "Third"), "no skinned mesh named 'Third' (the file has 'First', 'Second')");
  EXPECT_EQ(load_gltf(dir / "two.gltf", "Second").num_vertices(), test::make_toy_model().num_vertices());
}

}  // namespace
}  // namespace breastfit::model
