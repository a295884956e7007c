#pragma once
/// \file The registration energy at fixed correspondences: the terms of fit_options.h evaluated
/// at the evaluator's current parameters, with their Gauss–Newton normal equations.
#include <vector>

#include "breastfit/fit/correspondences.h"
#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/fit_summary.h"
#include "breastfit/fit/landmark_term.h"
#include "breastfit/fit/normal_equations.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::fit {

class Problem {
 public:
  /// Keeps references: all arguments must outlive the problem.
  Problem(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options,
          const std::vector<LandmarkTarget>& landmarks);

  model::PoseEvaluator& evaluator() { return ev_; }
  const model::PoseEvaluator& evaluator() const { return ev_; }
  const FitOptions& options() const { return options_; }
  ScanTarget& scan() { return scan_; }

  /// Re-chooses the model points of sliding landmarks (lowest breast points) at the current pose.
  void update_sliding_landmarks();
  /// Recomputes correspondences at the evaluator's current pose (every `stride`-th vertex).
  void update_correspondences(double max_distance_mm, int stride, bool with_reverse);
  /// Drops all correspondences (stages that use landmarks and priors only).
  void clear_correspondences();
  /// Energy at the evaluator's current parameters; with `eq`, accumulates its normal equations.
  EnergyBreakdown evaluate(NormalEquations* eq) const;

  /// Flips the scan's normal sign when most of them disagree with the posed template's normals.
  void orient_scan_normals(double max_distance_mm);

  const std::vector<Correspondence>& pairs() const { return pairs_; }
  const CorrespondenceStats& stats() const { return stats_; }
  const CorrespondenceStats& reverse_stats() const { return reverse_stats_; }
  /// Mean |point-to-plane distance| over the current pairs (∞ when none).
  double kept_mae_mm() const;

 private:
  const model::RiggedModel& model_;
  ScanTarget& scan_;
  const FitOptions& options_;
  std::vector<LandmarkTarget> landmarks_;  // a copy: sliding landmarks are re-chosen per iteration
  model::PoseEvaluator ev_;
  std::vector<Correspondence> pairs_;
  std::vector<ReverseCorrespondence> reverse_pairs_;
  CorrespondenceStats stats_, reverse_stats_;
  std::vector<Index> hints_, reverse_hints_;  // warm starts of the closest-point searches
};

}  // namespace breastfit::fit
