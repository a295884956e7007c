#include "breastfit/fit/correspondence_schedule.h"

#include <algorithm>
#include <cmath>

namespace breastfit::fit {

CorrespondenceSchedule::CorrespondenceSchedule(const CorrespondenceOptions& options, int num_data_stages)
    : options_(options), num_stages_(std::max(1, num_data_stages)) {}

double CorrespondenceSchedule::at(double t) const {
  const double ratio = options_.max_distance_end_mm / options_.max_distance_start_mm;
  return options_.max_distance_start_mm * std::pow(ratio, t);
}

double CorrespondenceSchedule::threshold(int data_stage, int it, int max_iterations) const {
  const double ramp = std::max(1, static_cast<int>(max_iterations * options_.schedule_ramp));
  return at((data_stage + std::min(1.0, it / ramp)) / num_stages_);
}

double CorrespondenceSchedule::stage_end(int data_stage) const { return at(double(data_stage + 1) / num_stages_); }

bool CorrespondenceSchedule::at_stage_end(int data_stage, int it, int max_iterations) const {
  return threshold(data_stage, it, max_iterations) <= stage_end(data_stage) * (1.0 + 1e-9);
}

}  // namespace breastfit::fit
