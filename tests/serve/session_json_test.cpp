#include "breastfit/serve/session_json.h"

#include <cstring>

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"

namespace breastfit::serve {
namespace {

TEST(SessionJson, LandmarksRoundTripAndBadEntries) {
  const std::vector<NamedPoint> pts = {{"nipple_R", Vec3(1, 2, 3)}, {"xiphoid", Vec3(-4, 5.5, 6)}};
  const LandmarkSet back = landmarks_from_json(landmarks_to_json(pts));
  ASSERT_EQ(back.points.size(), 2u);
  EXPECT_EQ(back.points[1].name, "xiphoid");
  EXPECT_EQ(back.points[1].position, Vec3(-4, 5.5, 6));
  EXPECT_EQ(back.declared_units, "mm");
  using nlohmann::json;
  EXPECT_THROW(landmarks_from_json(json::object()), InvalidInput);
  EXPECT_THROW(landmarks_from_json(json::parse(R"([{"name": "x"}])")), InvalidInput);
  EXPECT_THROW(landmarks_from_json(json::parse(R"([{"name": "x", "position": [1, 2]}])")), InvalidInput);
  EXPECT_THROW(landmarks_from_json(json::parse(R"([{"name": "x", "position": [1, "2", 3]}])")), InvalidInput);
}

TEST(SessionJson, ScanMeshBinaryLayout) {
  pipeline::PreparedScan s;
  s.mesh_mm.V.resize(3, 3);
  s.mesh_mm.V << 0, 0, 0, 1, 0, 0, 0, 2.5, 0;
  s.mesh_mm.F.resize(1, 3);
  s.mesh_mm.F << 0, 1, 2;
  const std::string b = scan_mesh_binary(s);
  ASSERT_EQ(b.size(), 8u + 9 * 4 + 3 * 4);
  uint32_t nv = 0, nf = 0, c = 0;
  float y = 0;
  std::memcpy(&nv, b.data(), 4);
  std::memcpy(&nf, b.data() + 4, 4);
  std::memcpy(&y, b.data() + 8 + 7 * 4, 4);
  std::memcpy(&c, b.data() + 8 + 9 * 4 + 2 * 4, 4);
  EXPECT_EQ(nv, 3u);
  EXPECT_EQ(nf, 1u);
  EXPECT_FLOAT_EQ(y, 2.5f);
  EXPECT_EQ(c, 2u);
}

TEST(SessionJson, ScanUvBinaryPerFaceCorner) {
  pipeline::PreparedScan s;
  s.mesh_mm.V.setZero(3, 3);
  s.mesh_mm.F.resize(1, 3);
  s.mesh_mm.F << 0, 1, 2;
  EXPECT_TRUE(scan_uv_binary(s).empty());
  s.mesh_mm.UV.resize(2, 2);
  s.mesh_mm.UV << 0.25, 0.5, 0.75, 1.0;
  s.mesh_mm.FUV.resize(1, 3);
  s.mesh_mm.FUV << 1, 0, 1;  // corners share and repeat coordinates
  const std::string b = scan_uv_binary(s);
  ASSERT_EQ(b.size(), 6 * sizeof(float));
  float uv[6];
  std::memcpy(uv, b.data(), sizeof uv);
  EXPECT_FLOAT_EQ(uv[0], 0.75f);
  EXPECT_FLOAT_EQ(uv[1], 1.0f);
  EXPECT_FLOAT_EQ(uv[2], 0.25f);
  EXPECT_FLOAT_EQ(uv[5], 1.0f);
}

TEST(SessionJson, SuggestionAndStatus) {
  auto o = std::make_shared<SuggestOutcome>();
  o->landmarks.push_back({"nipple_R", Vec3(1, 2, 3), 0.25, "breast tip on the scan"});
  o->server_ms = 400;
  const auto j = to_json(*o);
  ASSERT_EQ(j["landmarks"].size(), 1u);
  EXPECT_EQ(j["landmarks"][0]["name"], "nipple_R");
  EXPECT_EQ(j["landmarks"][0]["position"][2], 3.0);
  EXPECT_EQ(j["landmarks"][0]["confidence"], 0.25);
  EXPECT_EQ(j["landmarks"][0]["method"], "breast tip on the scan");
  // Placeable as landmarks.
  EXPECT_EQ(landmarks_from_json(j["landmarks"]).points[0].position, Vec3(1, 2, 3));
  FitStatus st;
  st.job = "suggest";
  st.suggestion = o;
  model::RiggedModel none;
  const auto s = to_json(st, none);
  EXPECT_EQ(s["job"], "suggest");
  EXPECT_EQ(s["suggestion"]["server_ms"], 400.0);
  EXPECT_TRUE(s["result"].is_null());
  EXPECT_FALSE(to_json(st, none, false).contains("suggestion"));
}

TEST(SessionJson, BodyFrameAxes) {
  mesh::BodyFrame f;
  f.body_to_world.block<3, 1>(0, 3) = Vec3(1, 2, 3);
  const auto j = to_json(f);
  EXPECT_EQ(j["origin"][2], 3.0);
  EXPECT_EQ(j["superior"][2], 1.0);
  EXPECT_EQ(j["source"], "landmarks");
}

}  // namespace
}  // namespace breastfit::serve
