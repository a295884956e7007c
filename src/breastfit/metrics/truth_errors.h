#pragma once
/// \file Errors against ground truth, for synthetic cases (breastfit synth) and experiments:
/// fitted surface to the true surface over its observed part, landmarks to true landmarks,
/// curves to true curves. (The external benchmark is scored by its own referee, not by this.)
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/mesh/landmarks.h"
#include "breastfit/metrics/distance_stats.h"

namespace breastfit::spatial {
class ClosestPointIndex;
}

namespace breastfit::metrics {

struct TruthErrors {
  DistanceStats surface;    ///< fitted vertices → truth surface (observed part, border matches excluded)
  DistanceStats landmarks;  ///< model landmarks → true landmarks (same names)
};

/// \param fitted_V   fitted template vertices, mm
/// \param truth      true surface, mm
/// \param scan       the scan (a truth point farther than observed_mm from it is unobserved)
/// \param model_landmarks / truth_landmarks  paired by name, mm
TruthErrors truth_errors(const Points& fitted_V, const TriangleMesh& truth, const fit::ScanTarget& scan,
                         const std::vector<NamedPoint>& model_landmarks,
                         const std::vector<NamedPoint>& truth_landmarks, double observed_mm = 5.0);

/// The same with the truth's closest-point index built once by the caller (experiments score
/// many fits of one case against the same truth).
TruthErrors truth_errors(const Points& fitted_V, const spatial::ClosestPointIndex& truth_index,
                         const fit::ScanTarget& scan, const std::vector<NamedPoint>& model_landmarks,
                         const std::vector<NamedPoint>& truth_landmarks, double observed_mm = 5.0);

/// Mean symmetric distance between two polylines (each resampled every `spacing_mm`, exact
/// point-to-segment distances both ways, mean of the two directed means), mm.
double curve_distance(const Curve& a, const Curve& b, double spacing_mm = 0.5);

}  // namespace breastfit::metrics
