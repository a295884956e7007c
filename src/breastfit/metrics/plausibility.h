#pragma once
/// \file Is a finished fit the shape of a torso? A fit can end "usable" (the solver converged,
/// fit/fit_summary.h) on something that is not an adult torso or not this scan's: a sphere, a
/// box, a torso scanned in the wrong units. Three signs, each with its threshold:
///  - the global scale is far from the template's size (an adult torso fitted at ×0.15 or ×3);
///  - many bounded parameters (bone scales per axis, blendshape weights) ended at a bound that
///    is not their rest value (1, 0): the shape space was pushed to its edge;
///  - the scan covers little of the model (metrics/surface_coverage.h), or the covered surface
///    error is large (its RMSE: a fit that is close in most places and far in many others).
/// An implausible fit is reported with every problem found (report.json "status": "implausible",
/// "plausibility"; report.html; docs/REPORT.md "Plausibility").
#include <string>
#include <vector>

#include "breastfit/metrics/distance_stats.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::metrics {

struct PlausibilityOptions {
  double min_global_scale = 0.6;        ///< the fitted global scale must lie in [min, max]
  double max_global_scale = 1.6;
  double bound_tolerance = 0.02;        ///< a parameter within this share of its range of a bound is at it
  double max_at_bound_fraction = 0.25;  ///< implausible when more of the bounded parameters are at a bound
  double min_coverage = 0.15;           ///< implausible below this covered fraction of the model
  double max_surface_rmse_mm = 5.0;     ///< implausible above this covered surface RMSE, mm
};

/// The judgement with its reasons.
struct Plausibility {
  bool plausible = true;
  std::vector<std::string> problems;  ///< one line each (empty when plausible)
  double global_scale = 1;
  int parameters_at_bound = 0;        ///< bone-scale axes and blendshape weights at a bound
  int bounded_parameters = 0;
  std::vector<std::string> at_bound;  ///< their names ("breast_R.scale_y", "ptosis", ...)
  double coverage = 0;                ///< covered fraction of the model
  double surface_rmse_mm = 0;         ///< covered surface RMSE
};

/// Judges a fit by its parameters, the covered fraction and the covered surface error.
Plausibility judge_plausibility(const model::RiggedModel& model, const model::PoseParams& params, double coverage,
                                const DistanceStats& surface, const PlausibilityOptions& options = {});

}  // namespace breastfit::metrics
