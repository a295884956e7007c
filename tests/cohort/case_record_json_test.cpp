// A case's record from report.json, and the record's JSON round trip.
#include "breastfit/cohort/case_record_json.h"

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"

namespace breastfit::cohort {
namespace {

nlohmann::json report(const char* status) {
  return nlohmann::json::parse(std::string(R"({"status": ")") + status + R"(", "time_s": 0.25, "iterations": 31,
    "verdict": "only 20% of the template on the scan",
    "table1": {"surface_mm": {"n": 100, "mae": 0.7, "max": 3.5},
               "landmarks_mm": {"n": 12, "mae": 4.5, "max": 9.0}},
    "breast_measurements": {"right": {"volume_ml": 410.0, "notch_to_nipple_mm": 190.0, "nipple_to_imf_mm": 70.0},
                            "left": {"volume_ml": 380.0, "notch_to_nipple_mm": 195.0, "nipple_to_imf_mm": null},
                            "inter_nipple_mm": 200.0, "symmetry_left_over_right": {"volume": 0.93}},
    "warnings": ["a", "b"]})");
}

TEST(CaseRecordJson, FromReport) {
  const CaseRecord r = case_record_from_report("p1", "p1.ply", report("ok"));
  EXPECT_EQ(r.status, "ok");
  EXPECT_TRUE(r.finished());
  EXPECT_TRUE(r.message.empty());
  EXPECT_EQ(r.time_s, 0.25);
  EXPECT_EQ(r.iterations, 31);
  EXPECT_EQ(r.surface_mae_mm, 0.7);
  EXPECT_EQ(r.surface_max_mm, 3.5);
  EXPECT_EQ(r.landmark_mae_mm, 4.5);
  EXPECT_EQ(r.volume_right_ml, 410.0);
  EXPECT_EQ(r.volume_left_ml, 380.0);
  EXPECT_EQ(r.volume_ratio, 0.93);
  EXPECT_EQ(r.notch_to_nipple_left_mm, 195.0);
  EXPECT_FALSE(r.nipple_to_imf_left_mm);  // null in the report
  EXPECT_EQ(r.inter_nipple_mm, 200.0);
  EXPECT_EQ(r.warnings, 2);
  EXPECT_FALSE(r.wall_s);

  const CaseRecord bad = case_record_from_report("p1", "p1.ply", report("not_usable"));
  EXPECT_EQ(bad.status, "not_usable");
  EXPECT_EQ(bad.message, "only 20% of the template on the scan");

  // Implausible: finished (its outputs are written), the problems are the message.
  nlohmann::json j = report("implausible");
  j["plausibility"] = {{"plausible", false}, {"problems", {"scale 0.4", "RMSE 8 mm"}}};
  const CaseRecord odd = case_record_from_report("p1", "p1.ply", j);
  EXPECT_EQ(odd.status, "implausible");
  EXPECT_TRUE(odd.finished());
  EXPECT_EQ(odd.message, "scale 0.4; RMSE 8 mm");
}

TEST(CaseRecordJson, NoLandmarksGivenIsNoLandmarkError) {
  nlohmann::json j = report("ok");
  j["table1"]["landmarks_mm"] = {{"n", 0}, {"mae", 0.0}, {"max", 0.0}};
  EXPECT_FALSE(case_record_from_report("p", "p.ply", j).landmark_mae_mm);
}

TEST(CaseRecordJson, RejectsReportsWithoutStatus) {
  EXPECT_THROW(case_record_from_report("p", "p.ply", nlohmann::json::object()), InvalidInput);
  EXPECT_THROW(case_record_from_report("p", "p.ply", nlohmann::json{{"status", "maybe"}}), InvalidInput);
  EXPECT_THROW(case_record_from_json(nlohmann::json{{"status", "ok"}}), InvalidInput);
}

TEST(CaseRecordJson, RoundTrip) {
  CaseRecord r = case_record_from_report("p, \"1\"", "dir/p.ply", report("ok"));
  r.wall_s = 1.5;
  r.resumed = true;
  const CaseRecord back = case_record_from_json(to_json(r));
  EXPECT_EQ(to_json(back), to_json(r));
  EXPECT_EQ(back.name, r.name);
  EXPECT_EQ(back.wall_s, 1.5);
  EXPECT_TRUE(back.resumed);
  EXPECT_FALSE(back.nipple_to_imf_left_mm);
}

}  // namespace
}  // namespace breastfit::cohort
