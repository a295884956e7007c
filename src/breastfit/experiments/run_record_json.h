#pragma once
/// \file RunRecord → JSON: one element of the "runs" arrays of experiments.json.
#include <nlohmann/json.hpp>

#include "breastfit/experiments/run_record.h"

namespace breastfit::experiments {

/// {"case", "pose", "status", "message", "time_s", "iterations", "initialization",
///  "landmarks_used", "template_vertices", "paper": {"surface", "landmarks"},
///  "truth": {"surface", "landmarks", "drawings_mm": {name: mm}} (only with truth)}.
/// Statistics as metrics::to_json (n, mae, sd, max, min, rmse). Non-finite numbers become null.
nlohmann::json to_json(const RunRecord& r);

}  // namespace breastfit::experiments
