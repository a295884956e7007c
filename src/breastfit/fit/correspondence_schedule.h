#pragma once
/// \file The correspondence distance threshold over the coarse-to-fine stages: it decays
/// geometrically from max_distance_start_mm (first data stage) to max_distance_end_mm (last),
/// stage k of n going from start·(end/start)^(k/n) to start·(end/start)^((k+1)/n) over the first
/// `schedule_ramp` share of its iterations, then staying at its end value. Convergence tests apply
/// only once a stage is at its end value (before, the energy changes with the threshold).
#include "breastfit/fit/fit_options.h"

namespace breastfit::fit {

class CorrespondenceSchedule {
 public:
  /// `num_data_stages`: how many stages use correspondences (the schedule is spread over them).
  CorrespondenceSchedule(const CorrespondenceOptions& options, int num_data_stages);
  /// Threshold at iteration `it` of a stage with `max_iterations`, the `data_stage`-th data stage.
  double threshold(int data_stage, int it, int max_iterations) const;
  /// The stage's end value.
  double stage_end(int data_stage) const;
  /// Whether iteration `it` runs at the stage's end value.
  bool at_stage_end(int data_stage, int it, int max_iterations) const;

 private:
  double at(double t) const;
  const CorrespondenceOptions& options_;
  int num_stages_;
};

}  // namespace breastfit::fit
