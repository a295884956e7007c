// ExperimentOptions → JSON: the grids and skipped experiments as run, with the fit options.
#include "breastfit/experiments/experiment_options_json.h"

#include <gtest/gtest.h>

#include "breastfit/fit/fit_options_json.h"

namespace breastfit::experiments {
namespace {

TEST(ExperimentOptionsJson, GridsSkipAndFitOptions) {
  ExperimentOptions o = ExperimentOptions::quick();
  o.skip = {"lambdas"};
  o.template_cache_dir = "templates";
  const nlohmann::json j = to_json(o);
  EXPECT_EQ(j.size(), 6u);  // the directories are not part of the configuration
  EXPECT_EQ(j["skip"], nlohmann::json::array({"lambdas"}));
  EXPECT_EQ(j["landmark_counts"], nlohmann::json::array({0, 3, 12}));
  EXPECT_EQ(j["blendshape_counts"], nlohmann::json::array({0, -1}));
  EXPECT_EQ(j["lambda_factors"], nlohmann::json::array({0.1, 10.0}));
  EXPECT_EQ(j["resolution_edges_mm"], nlohmann::json::array({16.0}));
  EXPECT_EQ(j["fit_options"], fit::to_json(o.fit));
}

}  // namespace
}  // namespace breastfit::experiments
