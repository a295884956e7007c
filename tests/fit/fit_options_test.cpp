#include "breastfit/fit/fit_options.h"

#include <cmath>

#include <gtest/gtest.h>

#include "breastfit/core/errors.h"
#include "breastfit/fit/energy_terms.h"

namespace breastfit::fit {
namespace {

TEST(FitOptions, DefaultsAreValid) { EXPECT_NO_THROW(FitOptions{}.validate()); }

TEST(EnergyWeights, HoldsEveryTermOfTheTableAtItsDefault) {
  const EnergyWeights w;
  ASSERT_EQ(w.lambdas().size(), energy_terms().size());
  for (size_t i = 0; i < energy_terms().size(); ++i) {
    EXPECT_EQ(w.lambdas()[i].first, energy_terms()[i].name);
    EXPECT_DOUBLE_EQ(w.lambda(energy_terms()[i].name), energy_terms()[i].default_lambda);
  }
  EXPECT_DOUBLE_EQ(w.lambda("data"), 0.25);  // the paper's λD as documented in REGISTRATION.md
}

TEST(EnergyWeights, SetsByNameAndRejectsUnknownTerms) {
  EnergyWeights w;
  w.set_lambda("scale", 3.0);
  EXPECT_DOUBLE_EQ(w.lambda("scale"), 3.0);
  EXPECT_THROW(w.set_lambda("smoothness", 1.0), InvalidInput);
  try {
    w.lambda("smoothness");
    FAIL() << "expected InvalidInput";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("data, reverse"), std::string::npos) << e.what();
  }
}

TEST(FitOptions, RejectsBadValuesNamingTheField) {
  auto invalid = [](auto change, const std::string& field) {
    FitOptions bad;
    change(bad);
    try {
      bad.validate();
      ADD_FAILURE() << "expected InvalidInput for " << field;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  invalid([](FitOptions& b) { b.detail.passes = -1; }, "detail.passes");
  invalid([](FitOptions& b) { b.detail.smoothness = -0.1; }, "detail.smoothness");
  invalid([](FitOptions& b) { b.detail.decay = 0; }, "detail.decay");
  invalid([](FitOptions& b) { b.detail.max_distance_mm = std::nan(""); }, "detail.max_distance_mm");
  invalid([](FitOptions& b) { b.detail.max_offset_mm = -1; }, "detail.max_offset_mm");
  invalid([](FitOptions& b) { b.weights.set_lambda("data", 0); }, "weights.lambda_data");
  invalid([](FitOptions& b) { b.weights.set_lambda("landmarks", -1); }, "weights.lambda_landmarks");
  invalid([](FitOptions& b) { b.weights.set_lambda("reverse", NAN); }, "weights.lambda_reverse");
  invalid([](FitOptions& b) { b.correspondences.max_distance_end_mm = 100; }, "correspondences.max_distance_end_mm");
  invalid([](FitOptions& b) { b.correspondences.schedule_ramp = 0; }, "correspondences.schedule_ramp");
  invalid([](FitOptions& b) { b.shape.max_iterations = -2; }, "shape.max_iterations");
  invalid([](FitOptions& b) { b.pose.correspondence_interval = -1; }, "pose.correspondence_interval");
  invalid([](FitOptions& b) { b.solver.function_tolerance = 0; }, "solver.function_tolerance");
  invalid([](FitOptions& b) { b.solver.min_damping = 1.0; }, "solver.min_damping");
  invalid([](FitOptions& b) { b.solver.max_step_attempts = 0; }, "solver.max_step_attempts");
  invalid([](FitOptions& b) { b.solver.min_gain_ratio = 1.0; }, "solver.min_gain_ratio");
  invalid([](FitOptions& b) { b.solver.hessian_interval = 0; }, "solver.hessian_interval");
  invalid([](FitOptions& b) { b.solver.vertex_tolerance_mm = -0.1; }, "solver.vertex_tolerance_mm");
  invalid([](FitOptions& b) { b.refit.max_iterations = 0; }, "refit.max_iterations");
  invalid([](FitOptions& b) { b.refit.vertex_tolerance_mm = NAN; }, "refit.vertex_tolerance_mm");
}

TEST(FitOptions, ADisableableTermMayBeSwitchedOff) {
  FitOptions o;
  o.weights.set_lambda("reverse", 0.0);
  EXPECT_NO_THROW(o.validate());
}

TEST(FitOptions, ListsTheStagesInRunOrder) {
  const FitOptions o;
  std::vector<std::string> names;
  for (const StageOptions* s : o.stages()) names.push_back(s->name);
  EXPECT_EQ(names, (std::vector<std::string>{"landmark_pose", "rigid", "pose", "shape", "refine"}));
}

}  // namespace
}  // namespace breastfit::fit
