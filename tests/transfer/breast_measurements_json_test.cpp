// BreastMeasurements → JSON: numbers where measured, null where an input was missing, the
// chest-wall rule and the warnings.
#include "breastfit/transfer/breast_measurements_json.h"

#include <gtest/gtest.h>

namespace breastfit::transfer {
namespace {

TEST(BreastMeasurementsJson, MeasuredValuesAreNumbers) {
  BreastMeasurements bigger;
  bigger.right = {420.0, 210.0, 75.0, Vec3(10, -80, 1200)};
  bigger.left = {380.0, 205.0, 72.0, Vec3(-10, -80, 1202)};
  bigger.inter_nipple_mm = 190.0;
  bigger.volume_ratio = 380.0 / 420.0;
  bigger.notch_to_nipple_ratio = 205.0 / 210.0;
  bigger.nipple_to_imf_ratio = 72.0 / 75.0;
  const nlohmann::json j = to_json(bigger);
  EXPECT_TRUE(j["right"]["volume_ml"].is_number());
  EXPECT_TRUE(j["symmetry_left_over_right"]["volume"].is_number());
  EXPECT_DOUBLE_EQ(j["left"]["volume_ml"].get<double>(), 380.0);
  EXPECT_DOUBLE_EQ(j["right"]["notch_to_nipple_mm"].get<double>(), 210.0);
  EXPECT_DOUBLE_EQ(j["left"]["nipple_to_imf_mm"].get<double>(), 72.0);
  EXPECT_EQ(j["right"]["imf_lowest_mm"], nlohmann::json::array({10.0, -80.0, 1200.0}));
  EXPECT_DOUBLE_EQ(j["inter_nipple_mm"].get<double>(), 190.0);
  EXPECT_DOUBLE_EQ(j["symmetry_left_over_right"]["nipple_to_imf"].get<double>(), 72.0 / 75.0);
  EXPECT_EQ(j["chest_wall"], "membrane");
  EXPECT_EQ(j["chest_wall_margin_mm"], 0.0);
  EXPECT_TRUE(j["method"].is_string());
  EXPECT_EQ(j["warnings"], nlohmann::json::array());
}

TEST(BreastMeasurementsJson, MissingValuesAreNullAndTheLayoutIsFixed) {
  BreastMeasurements m;
  m.volume_options.fill = ChestWallFill::ThinPlate;
  m.volume_options.margin_mm = 15.0;
  m.warnings = {"drawing breast_contour_L missing: no volume"};
  const nlohmann::json j = to_json(m);
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"chest_wall", "chest_wall_margin_mm", "inter_nipple_mm", "left", "method",
                                            "right", "symmetry_left_over_right", "warnings"}));
  for (const char* side : {"right", "left"})
    for (const char* k : {"volume_ml", "notch_to_nipple_mm", "nipple_to_imf_mm", "imf_lowest_mm"})
      EXPECT_TRUE(j[side][k].is_null()) << side << " " << k;
  for (const char* k : {"volume", "notch_to_nipple", "nipple_to_imf"})
    EXPECT_TRUE(j["symmetry_left_over_right"][k].is_null()) << k;
  EXPECT_TRUE(j["inter_nipple_mm"].is_null());
  EXPECT_EQ(j["chest_wall"], "thin_plate");
  EXPECT_EQ(j["chest_wall_margin_mm"], 15.0);
  EXPECT_EQ(j["warnings"][0], "drawing breast_contour_L missing: no volume");
}

}  // namespace
}  // namespace breastfit::transfer
