// RunRecord → JSON: the fields of every run, the statistics only when there are numbers, the
// truth only with truth, non-finite numbers as null.
#include "breastfit/experiments/run_record_json.h"

#include <gtest/gtest.h>

#include <cmath>

namespace breastfit::experiments {
namespace {

RunRecord record() {
  RunRecord r;
  r.case_id = "synth_001_standing";
  r.pose = "standing";
  r.message = "converged";
  r.time_s = 1.5;
  r.iterations = 12;
  r.initialization = "landmarks";
  r.landmarks_used = 12;
  r.template_vertices = 2000;
  r.paper_surface = metrics::distance_stats({1.0, 2.0});
  r.paper_landmarks = metrics::distance_stats({3.0});
  return r;
}

TEST(RunRecordJson, PaperNumbersWithoutTruth) {
  const nlohmann::json j = to_json(record());
  EXPECT_EQ(j["case"], "synth_001_standing");
  EXPECT_EQ(j["pose"], "standing");
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["message"], "converged");
  EXPECT_EQ(j["time_s"], 1.5);
  EXPECT_EQ(j["iterations"], 12);
  EXPECT_EQ(j["initialization"], "landmarks");
  EXPECT_EQ(j["landmarks_used"], 12);
  EXPECT_EQ(j["template_vertices"], 2000);
  EXPECT_EQ(j["paper"]["surface"]["n"], 2);
  EXPECT_EQ(j["paper"]["surface"]["mae"], 1.5);
  EXPECT_EQ(j["paper"]["landmarks"]["max"], 3.0);
  for (const char* k : {"n", "mae", "sd", "max", "min", "rmse"}) EXPECT_TRUE(j["paper"]["surface"].contains(k)) << k;
  EXPECT_FALSE(j.contains("truth"));
}

TEST(RunRecordJson, TruthAndNonFiniteNumbers) {
  RunRecord r = record();
  r.has_truth = true;
  r.truth_surface = metrics::distance_stats({0.5});
  r.truth_landmarks.mae = std::nan("");
  r.drawings_mm = {{"sternum", 2.5}, {"imf_R", std::nan("")}};
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j["truth"]["surface"]["mae"], 0.5);
  EXPECT_TRUE(j["truth"]["landmarks"]["mae"].is_null());
  EXPECT_EQ(j["truth"]["drawings_mm"]["sternum"], 2.5);
  EXPECT_TRUE(j["truth"]["drawings_mm"]["imf_R"].is_null());
}

TEST(RunRecordJson, AnErrorHasNoNumbers) {
  RunRecord r = record();
  r.status = "error";
  r.message = "cannot read scan";
  r.has_truth = true;
  const nlohmann::json j = to_json(r);
  EXPECT_EQ(j["status"], "error");
  EXPECT_EQ(j["message"], "cannot read scan");
  EXPECT_FALSE(j.contains("paper"));
  EXPECT_FALSE(j.contains("truth"));
}

}  // namespace
}  // namespace breastfit::experiments
