// MapResult → JSON: the per-point records in order and the summary counts.
#include "breastfit/transfer/surface_map_json.h"

#include <gtest/gtest.h>

namespace breastfit::transfer {
namespace {

MappedPoint mapped(const std::string& label, double distance, const std::string& confidence, bool supported) {
  MappedPoint p;
  p.markup = "points";
  p.label = label;
  p.input = Vec3(1, 2, 3);
  p.output = Vec3(4, 5, 6);
  p.distance_to_fit_a_mm = distance;
  p.projected = true;
  p.supported_by_scan_b = supported;
  p.scan_b_offset_mm = supported ? 0.5 : 0.0;
  p.confidence = confidence;
  return p;
}

TEST(SurfaceMapJson, PointsInOrderAndSummaryCounts) {
  MapResult r;
  r.points = {mapped("near", 2.0, "high", true), mapped("mid", 6.0, "medium", true), mapped("far", 25.0, "low", false)};
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j["summary"]["points"], 3);
  EXPECT_EQ(j["points"][2]["confidence"], "low");
  EXPECT_EQ(j["format"], "breastfit.map");
  EXPECT_EQ(j["version"], 1);
  EXPECT_EQ(j["units"], "mm");
  const auto& s = j["summary"];
  EXPECT_EQ(s["high"], 1);
  EXPECT_EQ(s["medium"], 1);
  EXPECT_EQ(s["low"], 1);
  EXPECT_DOUBLE_EQ(s["mean_distance_to_fit_a_mm"].get<double>(), 11.0);
  EXPECT_DOUBLE_EQ(s["max_distance_to_fit_a_mm"].get<double>(), 25.0);
  EXPECT_EQ(s["supported_by_scan_b"], 2);
  EXPECT_EQ(s["projected_on_scan_b"], 3);
  const auto& p = j["points"][0];
  EXPECT_EQ(p["markup"], "points");
  EXPECT_EQ(p["label"], "near");
  EXPECT_EQ(p["input_mm"], nlohmann::json::array({1.0, 2.0, 3.0}));
  EXPECT_EQ(p["output_mm"], nlohmann::json::array({4.0, 5.0, 6.0}));
  EXPECT_EQ(p["distance_to_fit_a_mm"], 2.0);
  EXPECT_EQ(p["projected_on_scan_b"], true);
  EXPECT_EQ(p["supported_by_scan_b"], true);
  EXPECT_EQ(p["scan_b_offset_mm"], 0.5);
}

TEST(SurfaceMapJson, EmptyResultHasZeroMeanDistance) {
  const nlohmann::json j = to_json(MapResult{});
  EXPECT_EQ(j["summary"]["points"], 0);
  EXPECT_EQ(j["summary"]["mean_distance_to_fit_a_mm"], 0.0);
  EXPECT_EQ(j["points"], nlohmann::json::array());
}

}  // namespace
}  // namespace breastfit::transfer
