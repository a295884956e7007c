#pragma once
/// \file FitOptions as JSON (the `--config` file of `breastfit register`, and report.json's
/// "options"). Keys are the field names; λs are `weights.lambda_<term>` for every term of
/// energy_terms.h; groups are objects ("weights", "correspondences", "solver", "detail", and one
/// per stage: "landmark_pose", "rigid", "pose", "shape", "refine").
#include <nlohmann/json_fwd.hpp>

#include "breastfit/fit/fit_options.h"

namespace breastfit::fit {

/// Reads any subset of the options. \throws InvalidInput for unknown keys (naming the expected
/// ones) or wrong types. Does not validate (FitOptions::validate does).
void update_from_json(FitOptions& options, const nlohmann::json& j);
/// All options as JSON.
nlohmann::json to_json(const FitOptions& options);

}  // namespace breastfit::fit
