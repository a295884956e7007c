#include "breastfit/fit/fit_options.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "breastfit/core/errors.h"

namespace breastfit::fit {
namespace {

TEST(FitOptions, DefaultsAreValidAndSurviveAJsonRoundTrip) {
  const FitOptions defaults;
  EXPECT_NO_THROW(defaults.validate());
  FitOptions changed;
  changed.weights.lambda_data = 0.7;
  changed.correspondences.kernel = RobustKernel::Huber;
  changed.detail.enabled = false;
  changed.detail.smoothness = 3.5;
  changed.refine.max_iterations = 7;
  FitOptions read;
  update_from_json(read, to_json(changed));
  EXPECT_EQ(to_json(read), to_json(changed));
  EXPECT_FALSE(read.detail.enabled);
  EXPECT_DOUBLE_EQ(read.detail.smoothness, 3.5);
}

TEST(FitOptions, ReadsASubsetAndKeepsTheRest) {
  FitOptions o;
  update_from_json(o, nlohmann::json::parse(R"({"detail": {"passes": 4}, "weights": {"lambda_landmarks": 20}})"));
  EXPECT_EQ(o.detail.passes, 4);
  EXPECT_DOUBLE_EQ(o.weights.lambda_landmarks, 20.0);
  EXPECT_DOUBLE_EQ(o.detail.smoothness, FitOptions{}.detail.smoothness);
  EXPECT_DOUBLE_EQ(o.weights.lambda_data, FitOptions{}.weights.lambda_data);
}

TEST(FitOptions, RejectsUnknownKeysWrongTypesAndBadValues) {
  FitOptions o;
  EXPECT_THROW(update_from_json(o, nlohmann::json::parse(R"({"detail": {"smoothnes": 1}})")), InvalidInput);
  EXPECT_THROW(update_from_json(o, nlohmann::json::parse(R"({"detail": {"enabled": "yes"}})")), InvalidInput);
  EXPECT_THROW(update_from_json(o, nlohmann::json::parse(R"({"correspondences": {"kernel": "cauchy"}})")),
               InvalidInput);
  EXPECT_THROW(update_from_json(o, nlohmann::json::parse(R"({"lambda_data": 1})")), InvalidInput);
  auto invalid = [](auto change) {
    FitOptions bad;
    change(bad);
    EXPECT_THROW(bad.validate(), InvalidInput);
  };
  invalid([](FitOptions& b) { b.detail.passes = -1; });
  invalid([](FitOptions& b) { b.detail.smoothness = -0.1; });
  invalid([](FitOptions& b) { b.detail.decay = 0; });
  invalid([](FitOptions& b) { b.detail.max_distance_mm = std::nan(""); });
  invalid([](FitOptions& b) { b.detail.max_offset_mm = -1; });
  invalid([](FitOptions& b) { b.weights.lambda_data = 0; });
  invalid([](FitOptions& b) { b.correspondences.max_distance_end_mm = 100; });
  invalid([](FitOptions& b) { b.shape.max_iterations = -2; });
}

}  // namespace
}  // namespace breastfit::fit
