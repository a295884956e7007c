#pragma once
/// \file ExperimentOptions → JSON: the "config" member of experiments.json (the grids that ran).
#include <nlohmann/json.hpp>

#include "breastfit/experiments/experiment_options.h"

namespace breastfit::experiments {

/// {"skip", "landmark_counts", "blendshape_counts", "lambda_factors", "resolution_edges_mm",
///  "fit_options" (fit::to_json)}; the cache and contract directories are not included.
nlohmann::json to_json(const ExperimentOptions& o);

}  // namespace breastfit::experiments
