// report.json of a real registration (the shared synthetic case of the report tests): the key
// layout and every number taken from the RegisterResult it summarises.
#include "breastfit/pipeline/register_report_json.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pipeline/report_test_case.h"

namespace breastfit::pipeline {
namespace {

std::vector<std::string> keys(const nlohmann::json& j) {
  std::vector<std::string> k;
  for (const auto& [name, v] : j.items()) k.push_back(name);
  return k;
}

TEST(RegisterReportJson, LayoutAndNumbersOfARealRegistration) {
  const RegisterResult& r = test::report_test_result();
  const nlohmann::json j = report_json(r);
  EXPECT_EQ(keys(j), (std::vector<std::string>{"breast_measurements", "converged", "drawings", "iterations",
                                               "plausibility", "point_cloud", "scan_coverage", "solver", "status",
                                               "stopping_reason", "table1", "termination", "time_s", "timings_s",
                                               "units", "verdict", "warnings"}));
  EXPECT_EQ(j["status"], r.usable() ? "ok" : "not_usable");
  // The surface error counts the covered vertices; the coverage says how many of all.
  EXPECT_EQ(j["scan_coverage"]["covered_vertices"], r.surface.n);
  EXPECT_EQ(j["scan_coverage"]["model_vertices"], r.fitted_mm.V.rows());
  EXPECT_GT(j["scan_coverage"]["fraction"].get<double>(), 0.3);
  EXPECT_TRUE(j["plausibility"]["plausible"].get<bool>()) << j["plausibility"].dump();
  EXPECT_EQ(j["verdict"], r.fit.summary.verdict.reason);
  EXPECT_EQ(j["converged"], r.fit.summary.converged());
  // Every phase of the pipeline is timed, the fit's own in between.
  for (const char* phase : {"scan_preparation", "index_build", "initialization", "stage:refine", "surface_detail",
                            "landmark_checks", "transfer", "measurements"})
    EXPECT_TRUE(j["timings_s"].contains(phase)) << phase;
  EXPECT_NEAR(j["timings_s"]["index_build"].get<double>() + r.fit.summary.seconds, r.time_s, 0.01);
  EXPECT_EQ(j["time_s"], r.time_s);
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["point_cloud"], r.scan.was_point_cloud);
  EXPECT_EQ(j["iterations"], r.fit.summary.iterations.size());
  EXPECT_EQ(j["stopping_reason"], r.fit.summary.termination_message);
  EXPECT_EQ(j["termination"], fit::to_string(r.fit.summary.termination));
  EXPECT_TRUE(j["solver"].is_object());

  const nlohmann::json& t = j["table1"];
  EXPECT_EQ(keys(t), (std::vector<std::string>{"landmark_errors_mm", "landmarks_mm", "surface_mm", "surface_model_only_mm"}));
  EXPECT_EQ(t["surface_mm"]["mae"], r.surface.mae);
  EXPECT_EQ(t["surface_model_only_mm"]["mae"], r.surface_model_only.mae);
  EXPECT_EQ(t["landmarks_mm"]["n"], r.landmarks.stats.n);
  ASSERT_EQ(t["landmark_errors_mm"].size(), r.landmarks.names.size());
  for (size_t i = 0; i < r.landmarks.names.size(); ++i)
    EXPECT_EQ(t["landmark_errors_mm"][r.landmarks.names[i]], r.landmarks.distances_mm[i]) << r.landmarks.names[i];

  ASSERT_EQ(j["drawings"].size(), r.drawings_on_scan.size());
  for (const auto& c : r.drawings_on_scan) {
    const nlohmann::json& d = j["drawings"][c.name];
    EXPECT_EQ(keys(d), (std::vector<std::string>{"closed", "length_mm", "mean_model_to_scan_mm", "points",
                                                 "supported_fraction"}))
        << c.name;
    EXPECT_EQ(d["closed"], c.closed);
    EXPECT_EQ(d["points"], c.points.rows());
    EXPECT_EQ(d["length_mm"], c.length_mm);
    EXPECT_EQ(d["supported_fraction"], c.supported_fraction);
  }
  EXPECT_EQ(j["breast_measurements"]["right"]["volume_ml"], r.breasts.right.volume_ml.value_or(-1));
  EXPECT_EQ(j["warnings"], r.warnings);
}

}  // namespace
}  // namespace breastfit::pipeline
