#include "breastfit/experiments/experiment_options.h"

#include <algorithm>
#include <cmath>

#include "breastfit/core/errors.h"

namespace breastfit::experiments {

const std::vector<LambdaSpec>& sensitivity_lambdas() {
  static const std::vector<LambdaSpec> specs = {{"lambda_data", "λD"},
                                                {"lambda_scale", "λS"},
                                                {"lambda_blendshapes", "λBS"},
                                                {"lambda_joints", "λJ"},
                                                {"lambda_landmarks", "λL"}};
  return specs;
}

double& lambda_field(fit::EnergyWeights& w, const std::string& field) {
  if (field == "lambda_data") return w.lambda_data;
  if (field == "lambda_reverse") return w.lambda_reverse;
  if (field == "lambda_landmarks") return w.lambda_landmarks;
  if (field == "lambda_scale") return w.lambda_scale;
  if (field == "lambda_blendshapes") return w.lambda_blendshapes;
  if (field == "lambda_joints") return w.lambda_joints;
  if (field == "lambda_continuity") return w.lambda_continuity;
  throw InvalidInput("unknown λ '" + field + "'");
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
