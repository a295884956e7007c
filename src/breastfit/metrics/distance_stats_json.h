#pragma once
/// \file DistanceStats → JSON, as report.json writes the paper's Table 1 columns.
#include <nlohmann/json.hpp>

#include "breastfit/metrics/distance_stats.h"

namespace breastfit::metrics {

/// {"n", "mae", "sd", "max", "min", "rmse"} (mm; n the number of distances).
nlohmann::json to_json(const DistanceStats& s);

}  // namespace breastfit::metrics
