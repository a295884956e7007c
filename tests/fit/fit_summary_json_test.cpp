#include "breastfit/fit/fit_summary_json.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace breastfit::fit {
namespace {

TEST(FitSummaryJson, ReportsTerminationVerdictEnergiesAndTimings) {
  FitSummary s;
  s.termination = Termination::ParameterTolerance;
  s.termination_message = "converged";
  s.verdict = {false, "not usable: only 3% of the template"};
  s.final_energy.terms = {{"data", 2.0}, {"landmarks", 1.0}};
  s.timings = {{"initialization", 0.5}, {"stage:pose", 0.25}};
  s.stages.push_back({"pose", 3, Termination::ParameterTolerance, 5.0, 3.0, 0.25});
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(j["termination"], "parameter_tolerance");
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["usable"], false);
  EXPECT_EQ(j["verdict"], "not usable: only 3% of the template");
  EXPECT_DOUBLE_EQ(j["energy"]["total"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["energy"]["landmarks"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["timings_s"]["stage:pose"].get<double>(), 0.25);
  EXPECT_EQ(j["stages"][0]["converged"], true);
}

TEST(FitSummaryJson, APhaseThatRanTwiceCountsBothRuns) {
  // The refine stage run again after a flagged landmark is timed as a second "stage:refine".
  FitSummary s;
  s.timings = {{"stage:refine", 0.25}, {"landmark_checks", 0.125}, {"stage:refine", 0.5}};
  const nlohmann::json j = to_json(s);
  EXPECT_DOUBLE_EQ(j["timings_s"]["stage:refine"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(j["timings_s"]["landmark_checks"].get<double>(), 0.125);
  EXPECT_EQ(j["timings_s"].size(), 2u);
}

}  // namespace
}  // namespace breastfit::fit
