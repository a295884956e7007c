#include "breastfit/fit/fit_summary.h"

#include <cstdio>

#include <nlohmann/json.hpp>

namespace breastfit::fit {

const char* to_string(Termination t) {
  switch (t) {
    case Termination::Converged: return "converged";
    case Termination::MaxIterations: return "max_iterations";
    case Termination::StepTooSmall: return "step_too_small";
    case Termination::NumericalFailure: return "numerical_failure";
    case Termination::NotUsable: return "not_converged";
  }
  return "unknown";
}

std::string FitSummary::brief() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "%s: %zu iterations, %.3f s, kept %d/%d correspondences, mean distance %.2f mm",
                to_string(termination), iterations.size(), seconds, final_correspondences.kept,
                final_correspondences.candidates, kept_mae_mm);
  return buf;
}

namespace {
nlohmann::json stats_json(const CorrespondenceStats& s) {
  return {{"candidates", s.candidates},
          {"kept", s.kept},
          {"rejected", {{"distance", s.rejected_distance}, {"boundary", s.rejected_boundary}, {"normal", s.rejected_normal}}},
          {"max_distance_mm", s.max_distance_mm}};
}
}  // namespace

nlohmann::json to_json(const FitSummary& s) {
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& st : s.stages)
    stages.push_back({{"name", st.name}, {"iterations", st.iterations}, {"termination", to_string(st.termination)},
                      {"initial_energy", st.initial_energy}, {"final_energy", st.final_energy}});
  nlohmann::json its = nlohmann::json::array();
  for (const auto& r : s.iterations)
    its.push_back({{"stage", r.stage}, {"iteration", r.iteration}, {"energy_before", r.energy_before},
                   {"energy_after", r.energy_after}, {"max_distance_mm", r.max_distance_mm}, {"kept", r.kept},
                   {"damping", r.damping}, {"step_norm", r.step_norm}, {"accepted", r.accepted}});
  const auto& e = s.final_energy;
  return {{"termination", to_string(s.termination)},
          {"stopping_reason", s.message},
          {"usable", s.usable()},
          {"iterations", s.iterations.size()},
          {"initialization", s.initialization},
          {"landmarks_used", s.landmarks_used},
          {"energy",
           {{"total", e.total()}, {"data", e.data}, {"reverse", e.reverse}, {"landmarks", e.landmarks},
            {"scale", e.scale}, {"blendshapes", e.blendshapes}, {"joints", e.joints}, {"continuity", e.continuity}}},
          {"correspondences", stats_json(s.final_correspondences)},
          {"reverse_correspondences", stats_json(s.final_reverse_correspondences)},
          {"kept_mae_mm", s.kept_mae_mm},
          {"surface_detail",
           {{"applied", s.detail.applied}, {"kept", s.detail.kept}, {"mean_abs_offset_mm", s.detail.mean_abs_mm},
            {"max_abs_offset_mm", s.detail.max_abs_mm}}},
          {"stages", stages},
          {"iteration_log", its},
          {"warnings", s.warnings},
          {"seconds", s.seconds}};
}

}  // namespace breastfit::fit
