#pragma once
/// \file The paper's registration errors (§2.10): surface distance from every fitted vertex to the
/// closest point of the scan (vertices whose closest scan point lies on the scan's open border are
/// left out, as over holes and beyond the scanned area there is nothing to compare with), and
/// distances between the fitted model's landmarks and the landmarks placed on the scan.
#include <string>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/landmark_target.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/metrics/distance_stats.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::metrics {

/// Distances (mm) of each vertex of V to the scan, skipping those whose closest scan feature is on
/// the scan's open border (when `skip_border`).
std::vector<double> surface_distances(const Points& V, const fit::ScanTarget& scan, bool skip_border = true);

struct LandmarkErrors {
  std::vector<std::string> names;
  std::vector<double> distances_mm;  ///< one per name
  DistanceStats stats;
};

/// ‖L_l(fitted) − ℓ_l‖ for each input landmark; `fitted_V` are the posed template vertices (mm) for
/// `params` (sliding landmarks are evaluated by their definition, see fit/sliding_landmarks.h).
LandmarkErrors landmark_errors(const model::RiggedModel& model, const Points& fitted_V,
                               const model::PoseParams& params, const std::vector<fit::LandmarkTarget>& targets);

}  // namespace breastfit::metrics
