#include "breastfit/fit/fit_options_json.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"
#include "breastfit/fit/energy_terms.h"

namespace breastfit::fit {
namespace {

std::string error_of(const char* text) {
  FitOptions o;
  try {
    update_from_json(o, nlohmann::json::parse(text));
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "";
}

TEST(FitOptionsJson, SurvivesARoundTrip) {
  FitOptions changed;
  changed.weights.set_lambda("data", 0.7);
  changed.weights.set_lambda("sliding_landmarks", 12.0);
  changed.correspondences.kernel = RobustKernel::Huber;
  changed.detail.enabled = false;
  changed.detail.smoothness = 3.5;
  changed.refine.max_iterations = 7;
  changed.shape.correspondence_interval = 3;
  changed.solver.function_tolerance = 3e-3;
  changed.solver.max_step_attempts = 5;
  changed.refit.final_threshold = false;
  changed.refit.max_iterations = 4;
  changed.refit.vertex_tolerance_mm = 0.25;
  FitOptions read;
  update_from_json(read, to_json(changed));
  EXPECT_EQ(to_json(read), to_json(changed));
  EXPECT_FALSE(read.detail.enabled);
  EXPECT_DOUBLE_EQ(read.detail.smoothness, 3.5);
  EXPECT_DOUBLE_EQ(read.weights.lambda("sliding_landmarks"), 12.0);
  EXPECT_EQ(read.solver.max_step_attempts, 5);
  EXPECT_EQ(read.shape.correspondence_interval, 3);
  EXPECT_FALSE(read.refit.final_threshold);
  EXPECT_EQ(read.refit.max_iterations, 4);
  EXPECT_DOUBLE_EQ(read.refit.vertex_tolerance_mm, 0.25);
}

TEST(FitOptionsJson, HasOneLambdaKeyPerEnergyTerm) {
  const nlohmann::json j = to_json(FitOptions{});
  for (const auto& t : energy_terms()) {
    const std::string key = "lambda_" + std::string(t.name);
    ASSERT_TRUE(j["weights"].contains(key)) << key;
    EXPECT_DOUBLE_EQ(j["weights"][key].get<double>(), t.default_lambda);
  }
  EXPECT_EQ(j["weights"].size(), energy_terms().size() + 1);  // + joint_translation_scale_mm
}

TEST(FitOptionsJson, ReadsASubsetAndKeepsTheRest) {
  FitOptions o;
  update_from_json(o, nlohmann::json::parse(
                          R"({"detail": {"passes": 4}, "weights": {"lambda_landmarks": 20}, "solver": {"hessian_interval": 1}})"));
  EXPECT_EQ(o.detail.passes, 4);
  EXPECT_DOUBLE_EQ(o.weights.lambda("landmarks"), 20.0);
  EXPECT_EQ(o.solver.hessian_interval, 1);
  EXPECT_DOUBLE_EQ(o.detail.smoothness, FitOptions{}.detail.smoothness);
  EXPECT_DOUBLE_EQ(o.weights.lambda("data"), FitOptions{}.weights.lambda("data"));
}

TEST(FitOptionsJson, RejectsUnknownKeysAndWrongTypesWithAClearMessage) {
  EXPECT_NE(error_of(R"({"detail": {"smoothnes": 1}})").find("unknown option 'detail.smoothnes'"), std::string::npos);
  EXPECT_NE(error_of(R"({"detail": {"enabled": "yes"}})").find("detail.enabled must be true or false"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"solver": {"max_step_attempts": 2.5}})").find("must be an integer"), std::string::npos);
  EXPECT_NE(error_of(R"({"correspondences": {"kernel": "cauchy"}})").find("cauchy"), std::string::npos);
  EXPECT_NE(error_of(R"({"lambda_data": 1})").find("unknown option 'lambda_data'"), std::string::npos);
  EXPECT_NE(error_of(R"({"weights": {"lambda_smooth": 1}})").find("lambda_sliding_landmarks"), std::string::npos);
  EXPECT_NE(error_of(R"({"function_tolerance": 1e-3})").find("moved into \"solver\""), std::string::npos);
  EXPECT_NE(error_of(R"([1, 2])").find("must be an object"), std::string::npos);
}

}  // namespace
}  // namespace breastfit::fit
