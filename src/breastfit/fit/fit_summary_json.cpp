#include "breastfit/fit/fit_summary_json.h"

#include <cmath>

#include <nlohmann/json.hpp>

namespace breastfit::fit {

nlohmann::json to_json(const CorrespondenceStats& s) {
  return {{"candidates", s.candidates},
          {"kept", s.kept},
          {"rejected", {{"distance", s.rejected_distance}, {"boundary", s.rejected_boundary}, {"normal", s.rejected_normal}}},
          {"max_distance_mm", s.max_distance_mm}};
}

nlohmann::json to_json(const EnergyBreakdown& e) {
  nlohmann::json out = {{"total", e.total()}};
  for (const auto& [name, value] : e.terms) out[name] = value;
  return out;
}

nlohmann::json timings_json(const std::vector<PhaseTime>& timings) {
  nlohmann::json out = nlohmann::json::object();
  // A phase that ran twice (the refine stage again after a flagged landmark) counts both runs.
  for (const auto& p : timings) out[p.phase] = out.value(p.phase, 0.0) + p.seconds;
  return out;
}

nlohmann::json landmark_checks_json(const std::vector<LandmarkCheck>& checks) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& c : checks)
  {
    out[c.name] = {{"distance_mm", c.distance_mm}, {"tolerance_mm", c.tolerance_mm}, {"factor", c.factor},
                   {"flagged", c.flagged}};
    if (c.anatomy_distance_mm >= 0) {
      out[c.name]["anatomy_distance_mm"] = c.anatomy_distance_mm;
      out[c.name]["anatomy_tolerance_mm"] = c.anatomy_tolerance_mm;
      out[c.name]["anatomy"] = c.anatomy;
    }
    if (c.predicted_distance_mm >= 0) {
      out[c.name]["predicted_distance_mm"] = c.predicted_distance_mm;
      out[c.name]["predicted_tolerance_mm"] = c.predicted_tolerance_mm;
    }
  }
  return out;
}

nlohmann::json orientation_json(const OrientationSummary& o) {
  if (!o.searched) return nullptr;
  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& c : o.candidates)
    candidates.push_back({{"name", c.name}, {"score_mm", c.score}, {"refined", c.refined}});
  return {{"chosen", o.chosen},
          {"runner_up", o.runner_up},
          {"margin", std::isfinite(o.margin) ? nlohmann::json(o.margin) : nlohmann::json(nullptr)},
          {"confident", o.confident},
          {"body_frame", o.body_frame},
          {"arm_abduction_deg", {{"R", o.arm_abduction_deg[0]}, {"L", o.arm_abduction_deg[1]}}},
          {"arm_pose", o.arm_pose},
          {"candidates", candidates}};
}

nlohmann::json to_json(const FitSummary& s) {
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& st : s.stages)
    stages.push_back({{"name", st.name}, {"iterations", st.iterations}, {"termination", to_string(st.termination)},
                      {"converged", is_convergence(st.termination)}, {"initial_energy", st.initial_energy},
                      {"final_energy", st.final_energy}, {"seconds", st.seconds}});
  nlohmann::json its = nlohmann::json::array();
  for (const auto& r : s.iterations)
    its.push_back({{"stage", r.stage}, {"iteration", r.iteration}, {"energy_before", r.energy_before},
                   {"energy_after", r.energy_after}, {"predicted_decrease", r.predicted_decrease},
                   {"gain_ratio", r.gain_ratio}, {"gradient_max", r.gradient_max},
                   {"max_distance_mm", r.max_distance_mm}, {"kept", r.kept}, {"damping", r.damping},
                   {"step_norm", r.step_norm}, {"accepted", r.accepted}, {"seconds", r.seconds}});
  return {{"termination", to_string(s.termination)},
          {"converged", s.converged()},
          {"stopping_reason", s.termination_message},
          {"usable", s.usable()},
          {"verdict", s.verdict.reason},
          {"iterations", s.iterations.size()},
          {"initialization", s.initialization},
          {"initialization_detail", s.initialization_detail},
          {"orientation", orientation_json(s.orientation)},
          {"anatomical_landmarks", s.anatomical_landmarks},
          {"anatomical_landmark_names", s.anatomical_landmark_names},
          {"landmarks_used", s.landmarks_used},
          {"energy", to_json(s.final_energy)},
          {"correspondences", to_json(s.final_correspondences)},
          {"reverse_correspondences", to_json(s.final_reverse_correspondences)},
          {"kept_mae_mm", s.kept_mae_mm},
          {"surface_detail",
           {{"applied", s.detail.applied}, {"kept", s.detail.kept}, {"mean_abs_offset_mm", s.detail.mean_abs_mm},
            {"max_abs_offset_mm", s.detail.max_abs_mm}}},
          {"landmark_check", landmark_checks_json(s.landmark_checks)},
          {"stages", stages},
          {"iteration_log", its},
          {"timings_s", timings_json(s.timings)},
          {"warnings", s.warnings},
          {"seconds", s.seconds}};
}

}  // namespace breastfit::fit
