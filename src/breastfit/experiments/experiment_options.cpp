#include "breastfit/experiments/experiment_options.h"

#include <algorithm>
#include <cmath>

#include "breastfit/core/errors.h"

namespace breastfit::experiments {

const std::vector<LambdaSpec>& sensitivity_lambdas() {
  // The paper's λL weighs all 12 landmarks, which the fit splits into material and sliding ones.
  static const std::vector<LambdaSpec> specs = {{"lambda_data", "λD", {"data"}},
                                                {"lambda_scale", "λS", {"scale"}},
                                                {"lambda_blendshapes", "λBS", {"blendshapes"}},
                                                {"lambda_joints", "λJ", {"joints"}},
                                                {"lambda_landmarks", "λL", {"landmarks", "sliding_landmarks"}}};
  return specs;
}

namespace {
// The terms of a sensitivity λ; any other "lambda_<term>" stands for that one term.
std::vector<std::string> terms_of(const std::string& field) {
  for (const auto& spec : sensitivity_lambdas())
    if (spec.field == field) return spec.terms;
  if (field.rfind("lambda_", 0) != 0) throw InvalidInput("unknown λ '" + field + "'");
  return {field.substr(7)};
}
}  // namespace

double lambda_value(const fit::EnergyWeights& w, const std::string& field) {
  return w.lambda(terms_of(field).front());
}

void scale_lambda(fit::EnergyWeights& w, const std::string& field, double factor) {
  for (const auto& term : terms_of(field)) w.set_lambda(term, w.lambda(term) * factor);
}

bool ExperimentOptions::runs(const std::string& experiment) const {
  return std::find(skip.begin(), skip.end(), experiment) == skip.end();
}

ExperimentOptions ExperimentOptions::quick() {
  ExperimentOptions o;
  o.landmark_counts = {0, 3, 12};
  o.blendshape_counts = {0, -1};
  o.lambda_factors = {0.1, 10.0};
  o.resolution_edges_mm = {16.0};
  return o;
}

void ExperimentOptions::validate() const {
  for (const auto& s : skip)
    if (std::find(kExperimentNames.begin(), kExperimentNames.end(), s) == kExperimentNames.end())
      throw InvalidInput("unknown experiment '" + s + "' (expected: table1, landmarks, blendshapes, lambdas, resolution)");
  for (int n : landmark_counts)
    if (n < 0 || n > 12) throw InvalidInput("landmark count " + std::to_string(n) + " is outside [0, 12]");
  for (int n : blendshape_counts)
    if (n < -1) throw InvalidInput("blendshape count " + std::to_string(n) + " is negative (-1 = all)");
  for (double f : lambda_factors)
    if (!(f > 0) || !std::isfinite(f)) throw InvalidInput("λ factor " + std::to_string(f) + " must be positive");
  for (double e : resolution_edges_mm)
    if (!(e >= 8.0 && e <= 40.0))
      throw InvalidInput("template edge " + std::to_string(e) + " mm is outside the builder's [8, 40] mm");
  fit.validate();
}

}  // namespace breastfit::experiments
