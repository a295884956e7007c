#pragma once
/// \file The registration's minimiser (as Ceres' trust_region_minimizer): stage by stage (coarse to
/// fine), each outer iteration recomputes the correspondences at the current pose (ICP; every
/// stage.correspondence_interval-th iteration, the pairs kept in between), lets the
/// terms update, builds the normal equations (the Hessian JᵀWJ every solver.hessian_interval-th
/// iteration, the gradient every time), asks the damping strategy (lm_strategy.h) for steps until
/// one lowers the energy, and applies the convergence tests (solver options) once the stage's
/// correspondence threshold has reached its end value (correspondence_schedule.h).
#include <vector>

#include "breastfit/fit/fit_summary.h"
#include "breastfit/fit/problem.h"
#include "breastfit/model/pose_params.h"

namespace breastfit::fit {

/// The parameters `stage` moves (indices into the full vector of `layout`): the similarity, the
/// bones and the first `max_shapes` blendshapes (< 0: all), as the stage says.
std::vector<int> active_parameters(const model::ParamLayout& layout, const StageOptions& stage, int max_shapes);

/// Runs `stages` in order from `params` (updated in place). Appends stage summaries, iteration
/// records and per-stage times ("stage:<name>") to `summary`. Bone scales and blendshape weights
/// stay within their bounds. Stops early (termination Aborted) when `on_iteration` returns Abort.
/// \returns the termination of the last stage run, or Aborted / NumericalFailure.
Termination minimize_stages(Problem& problem, const std::vector<StageOptions>& stages, model::PoseParams& params,
                            FitSummary& summary, const IterationCallback& on_iteration = {});

}  // namespace breastfit::fit
