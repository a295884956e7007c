#pragma once
/// \file The landmark term (paper eq. 9): squared distances between model landmarks and the
/// landmarks placed on the scan.
#include <string>
#include <vector>

#include "breastfit/fit/normal_equations.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::fit {

/// One input landmark matched to a model landmark.
struct LandmarkTarget {
  std::string name;
  int model_landmark = 0;        ///< index into RiggedModel::landmarks
  Vec3 position = Vec3::Zero();  ///< on the scan, mm
};

/// scale · Σ_l ‖L_l(θ) − ℓ_l‖²; with `eq`, also its normal equations. Returns the cost.
double add_landmark_term(const model::PoseEvaluator& ev, const std::vector<LandmarkTarget>& targets, double scale,
                         NormalEquations* eq);

}  // namespace breastfit::fit
