#include "breastfit/experiments/experiment_options_json.h"

#include "breastfit/fit/fit_options_json.h"

namespace breastfit::experiments {

nlohmann::json to_json(const ExperimentOptions& o) {
  return {{"skip", o.skip},
          {"landmark_counts", o.landmark_counts},
          {"blendshape_counts", o.blendshape_counts},
          {"lambda_factors", o.lambda_factors},
          {"resolution_edges_mm", o.resolution_edges_mm},
          {"fit_options", fit::to_json(o.fit)}};
}

}  // namespace breastfit::experiments
