#pragma once
/// \file RegisterResult → JSON: the content of report.json, the summary `breastfit register`
/// (and `demo`, and the experiments' contract outputs) writes next to the fitted model.
#include <nlohmann/json.hpp>

#include "breastfit/pipeline/register_scan.h"

namespace breastfit::pipeline {

/// report.json: {"time_s", "status": "ok" | "implausible" | "not_usable", "units", "point_cloud", "iterations",
///  "stopping_reason", "termination", "solver" (fit::to_json of the solver summary),
///  "table1": {"surface_mm", "surface_model_only_mm", "landmarks_mm" (metrics::to_json),
///             "landmark_errors_mm": {name: mm}},
///  "drawings": {name: {"closed", "points", "length_mm", "supported_fraction", "mean_model_to_scan_mm"}},
///  "breast_measurements" (transfer::to_json), "warnings": [...],
///  "scan_coverage": {"model_vertices", "covered_vertices", "fraction", "max_distance_mm",
///                    "max_normal_angle_deg", "border_excluded"} (metrics/surface_coverage.h),
///  "plausibility": {"plausible", "problems", "global_scale", "parameters_at_bound",
///                   "bounded_parameters"} (metrics/plausibility.h),
///  "provenance" and "run" (provenance_json.h) when the result carries its provenance}.
nlohmann::json report_json(const RegisterResult& r);

}  // namespace breastfit::pipeline
