#pragma once
/// \file Levenberg–Marquardt over the template's parameters, stage by stage (coarse to fine),
/// with correspondences recomputed at every outer iteration (ICP) and a shrinking distance threshold.
#include <functional>
#include <vector>

#include "breastfit/fit/fit_summary.h"
#include "breastfit/fit/problem.h"
#include "breastfit/model/pose_params.h"

namespace breastfit::fit {


/// Runs `stages` in order from `params` (updated in place). Appends stage summaries and iteration
/// records to `summary`. Bone scales and blendshape weights stay within their bounds.
/// \returns false on numerical failure (non-finite energy).
bool solve_stages(Problem& problem, const std::vector<StageOptions>& stages, model::PoseParams& params,
                  FitSummary& summary, const IterationCallback& on_iteration = {});

}  // namespace breastfit::fit
