#pragma once
/// \file The numbers of one registration run in an experiment: time, the paper's errors (model
/// to scan, model landmarks to the landmarks placed on the scan) and, when the case has ground
/// truth, the errors against it (surface, landmarks, drawings).
#include <string>
#include <utility>
#include <vector>

#include "breastfit/metrics/distance_stats.h"

namespace breastfit::experiments {

struct RunRecord {
  std::string case_id;
  std::string pose;                    ///< "standing", "supine" or "unknown"
  /// "ok" (usable), "not_usable" (the solver converged but the verdict rejects the fit),
  /// "not_converged" (not usable and the solver did not converge: cap, abort, numerical failure)
  /// or "error" (no fit). See run_status.
  std::string status = "ok";
  std::string message;                 ///< the solver's stopping reason, or the error
  double time_s = 0;                   ///< scan and landmarks in memory → fitted parameters (index build included)
  int iterations = 0;
  std::string initialization;          ///< "landmarks" or "landmark-free"
  int landmarks_used = 0;              ///< landmarks in the energy
  int template_vertices = 0;

  /// The paper's way (§2.10): fitted vertices → scan (border matches excluded), and model
  /// landmarks → every landmark placed on the scan (all 12, used in the fit or not).
  metrics::DistanceStats paper_surface, paper_landmarks;

  bool has_truth = false;
  /// Against the ground truth: fitted vertices → truth surface over its observed part,
  /// model landmarks → true landmarks, transferred drawings → true drawings (mean symmetric
  /// distance, metrics::curve_distance) for each true curve (NaN when the fit has no such drawing).
  metrics::DistanceStats truth_surface, truth_landmarks;
  std::vector<std::pair<std::string, double>> drawings_mm;

  /// Numbers exist (status "ok", "not_usable" or "not_converged").
  bool has_numbers() const { return status != "error"; }
};

}  // namespace breastfit::experiments
