#include "breastfit/fit/fit_options.h"

#include <cmath>
#include <sstream>

#include "breastfit/core/errors.h"
#include "breastfit/fit/energy_terms.h"

namespace breastfit::fit {
namespace {

void require(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok) {
    std::ostringstream s;
    s << "option " << field << " = " << value << ": " << rule;
    throw InvalidInput(s.str());
  }
}

bool positive(double v) { return std::isfinite(v) && v > 0; }

void validate_stage(const StageOptions& s) {
  require(s.max_iterations >= 0 && s.max_iterations <= 1000, s.name + ".max_iterations", s.max_iterations,
          "must be in [0, 1000]");
  require(s.vertex_stride >= 1 && s.vertex_stride <= 64, s.name + ".vertex_stride", s.vertex_stride,
          "must be in [1, 64]");
  require(s.correspondence_interval >= 0 && s.correspondence_interval <= 100, s.name + ".correspondence_interval",
          s.correspondence_interval, "must be in [0, 100] (0: automatic)");
}

void validate_weights(const EnergyWeights& w) {
  for (const auto& [name, lambda] : w.lambdas()) {
    const TermSpec* spec = find_energy_term(name);
    if (spec->can_disable)
      require(std::isfinite(lambda), "weights.lambda_" + name, lambda, "must be finite (<= 0 disables)");
    else
      require(positive(lambda), "weights.lambda_" + name, lambda, "must be finite and > 0");
  }
  require(positive(w.joint_translation_scale_mm), "weights.joint_translation_scale_mm", w.joint_translation_scale_mm,
          "must be finite and > 0");
}

void validate_correspondences(const CorrespondenceOptions& c) {
  require(positive(c.max_distance_start_mm), "correspondences.max_distance_start_mm", c.max_distance_start_mm, "must be > 0");
  require(positive(c.max_distance_end_mm) && c.max_distance_end_mm <= c.max_distance_start_mm,
          "correspondences.max_distance_end_mm", c.max_distance_end_mm, "must be > 0 and <= max_distance_start_mm");
  require(c.schedule_ramp > 0 && c.schedule_ramp <= 1, "correspondences.schedule_ramp", c.schedule_ramp,
          "must be in (0, 1]");
  require(c.max_normal_angle_deg > 0 && c.max_normal_angle_deg <= 180, "correspondences.max_normal_angle_deg",
          c.max_normal_angle_deg, "must be in (0, 180]");
  require(c.point_to_point_weight >= 0 && c.point_to_point_weight <= 1, "correspondences.point_to_point_weight",
          c.point_to_point_weight, "must be in [0, 1]");
  require(positive(c.kernel_scale_mm), "correspondences.kernel_scale_mm", c.kernel_scale_mm, "must be > 0");
  require(c.reverse_samples >= 0 && c.reverse_samples <= 1000000, "correspondences.reverse_samples", c.reverse_samples,
          "must be in [0, 1e6]");
}

void validate_solver(const SolverOptions& s) {
  require(positive(s.function_tolerance), "solver.function_tolerance", s.function_tolerance, "must be > 0");
  require(std::isfinite(s.gradient_tolerance) && s.gradient_tolerance >= 0, "solver.gradient_tolerance",
          s.gradient_tolerance, "must be finite and >= 0");
  require(std::isfinite(s.parameter_tolerance) && s.parameter_tolerance >= 0, "solver.parameter_tolerance",
          s.parameter_tolerance, "must be finite and >= 0");
  require(positive(s.initial_damping), "solver.initial_damping", s.initial_damping, "must be > 0");
  require(positive(s.min_damping) && s.min_damping <= s.initial_damping, "solver.min_damping", s.min_damping,
          "must be > 0 and <= initial_damping");
  require(positive(s.max_damping) && s.max_damping >= s.initial_damping, "solver.max_damping", s.max_damping,
          "must be finite and >= initial_damping");
  require(std::isfinite(s.damping_decrease) && s.damping_decrease > 1, "solver.damping_decrease", s.damping_decrease,
          "must be finite and > 1");
  require(std::isfinite(s.damping_increase) && s.damping_increase > 1, "solver.damping_increase", s.damping_increase,
          "must be finite and > 1");
  require(s.good_gain_ratio >= 0 && s.good_gain_ratio < 1, "solver.good_gain_ratio", s.good_gain_ratio,
          "must be in [0, 1)");
  require(s.max_step_attempts >= 1 && s.max_step_attempts <= 100, "solver.max_step_attempts", s.max_step_attempts,
          "must be in [1, 100]");
  require(s.min_gain_ratio >= 0 && s.min_gain_ratio < 1, "solver.min_gain_ratio", s.min_gain_ratio, "must be in [0, 1)");
  require(s.hessian_interval >= 1 && s.hessian_interval <= 10, "solver.hessian_interval", s.hessian_interval,
          "must be in [1, 10]");
  require(std::isfinite(s.vertex_tolerance_mm) && s.vertex_tolerance_mm >= 0, "solver.vertex_tolerance_mm",
          s.vertex_tolerance_mm, "must be finite and >= 0");
}

void validate_refit(const RefitOptions& r) {
  require(r.max_iterations >= 1 && r.max_iterations <= 1000, "refit.max_iterations", r.max_iterations,
          "must be in [1, 1000]");
  require(std::isfinite(r.vertex_tolerance_mm) && r.vertex_tolerance_mm >= 0, "refit.vertex_tolerance_mm",
          r.vertex_tolerance_mm, "must be finite and >= 0");
}

void validate_detail(const SurfaceDetailOptions& d) {
  require(d.passes >= 0 && d.passes <= 20, "detail.passes", d.passes, "must be in [0, 20]");
  require(d.smoothness >= 0 && std::isfinite(d.smoothness), "detail.smoothness", d.smoothness, "must be finite and >= 0");
  require(positive(d.decay), "detail.decay", d.decay, "must be finite and > 0");
  require(positive(d.max_distance_mm), "detail.max_distance_mm", d.max_distance_mm, "must be finite and > 0");
  require(d.max_offset_mm >= 0 && std::isfinite(d.max_offset_mm), "detail.max_offset_mm", d.max_offset_mm,
          "must be finite and >= 0");
  require(positive(d.kernel_scale_mm), "detail.kernel_scale_mm", d.kernel_scale_mm, "must be finite and > 0");
}

}  // namespace

const char* to_string(RobustKernel k) {
  switch (k) {
    case RobustKernel::None: return "none";
    case RobustKernel::Huber: return "huber";
    case RobustKernel::GemanMcClure: return "geman_mcclure";
  }
  return "none";
}

EnergyWeights::EnergyWeights() {
  for (const auto& t : energy_terms()) lambdas_.emplace_back(std::string(t.name), t.default_lambda);
}

double EnergyWeights::lambda(std::string_view term) const {
  for (const auto& [name, value] : lambdas_)
    if (name == term) return value;
  throw InvalidInput("'" + std::string(term) + "' is not an energy term (expected one of: " + energy_term_names() + ")");
}

void EnergyWeights::set_lambda(std::string_view term, double value) {
  for (auto& [name, v] : lambdas_)
    if (name == term) {
      v = value;
      return;
    }
  throw InvalidInput("'" + std::string(term) + "' is not an energy term (expected one of: " + energy_term_names() + ")");
}

bool FitOptions::uses_reverse_term() const {
  return weights.lambda("reverse") > 0 && correspondences.reverse_samples > 0;
}

std::vector<const StageOptions*> FitOptions::stages() const { return {&landmark_pose, &rigid, &pose, &shape, &refine}; }
std::vector<StageOptions*> FitOptions::stages() { return {&landmark_pose, &rigid, &pose, &shape, &refine}; }

void FitOptions::validate() const {
  validate_weights(weights);
  validate_correspondences(correspondences);
  for (const StageOptions* s : stages()) validate_stage(*s);
  validate_solver(solver);
  validate_detail(detail);
  validate_refit(refit);
  require(landmark_warning_mm > 0, "landmark_warning_mm", landmark_warning_mm, "must be > 0");
  require(positive(landmark_check_mm), "landmark_check_mm", landmark_check_mm, "must be finite and > 0");
  require(positive(nipple_tip_check_mm), "nipple_tip_check_mm", nipple_tip_check_mm, "must be finite and > 0");
  require(positive(notch_check_mm), "notch_check_mm", notch_check_mm, "must be finite and > 0");
  require(positive(max_surface_mae_mm), "max_surface_mae_mm", max_surface_mae_mm, "must be > 0");
  require(orientation_min_margin >= 0, "orientation_min_margin", orientation_min_margin, "must be >= 0");
  require(min_kept_fraction >= 0 && min_kept_fraction <= 1, "min_kept_fraction", min_kept_fraction, "must be in [0, 1]");
  require(threads >= 0, "threads", threads, "must be >= 0 (0: all cores)");
}

}  // namespace breastfit::fit
