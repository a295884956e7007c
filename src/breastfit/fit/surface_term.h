#pragma once
/// \file The data terms: model → scan (paper eq. 8, point-to-plane mixed with point-to-point)
/// and the optional reverse term scan → model.
#include <vector>

#include "breastfit/fit/correspondences.h"
#include "breastfit/fit/normal_equations.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::fit {

/// Σ_c w_c [(1−μ)(n_c·(M_i − p_c))² + μ‖M_i − p_c‖²] · scale at the evaluator's current pose;
/// with `eq`, also accumulates its Gauss–Newton normal equations. Returns the cost.
double add_data_term(const model::PoseEvaluator& ev, const std::vector<Correspondence>& pairs, double mu,
                     double scale, NormalEquations* eq);

/// Σ_c w_c (n_c·(X_c(θ) − s_c))² · scale with X_c the correspondence's point on the posed model.
double add_reverse_term(const model::PoseEvaluator& ev, const std::vector<ReverseCorrespondence>& pairs,
                        double scale, NormalEquations* eq);

}  // namespace breastfit::fit
