#include "breastfit/fit/fit_summary.h"

#include <cstdio>

namespace breastfit::fit {

const char* to_string(Termination t) {
  switch (t) {
    case Termination::FunctionTolerance: return "function_tolerance";
    case Termination::GradientTolerance: return "gradient_tolerance";
    case Termination::ParameterTolerance: return "parameter_tolerance";
    case Termination::NoFurtherDecrease: return "no_further_decrease";
    case Termination::IterationCap: return "iteration_cap";
    case Termination::Aborted: return "aborted";
    case Termination::NumericalFailure: return "numerical_failure";
  }
  return "unknown";
}

bool is_convergence(Termination t) {
  return t == Termination::FunctionTolerance || t == Termination::GradientTolerance ||
         t == Termination::ParameterTolerance || t == Termination::NoFurtherDecrease;
}

double EnergyBreakdown::total() const {
  double sum = 0;
  for (const auto& [name, e] : terms) sum += e;
  return sum;
}

double EnergyBreakdown::operator[](const std::string& name) const {
  for (const auto& [n, e] : terms)
    if (n == name) return e;
  return 0.0;
}

double FitSummary::phase_seconds(const std::string& phase) const {
  for (const auto& p : timings)
    if (p.phase == phase) return p.seconds;
  return 0.0;
}

std::string FitSummary::brief() const {
  char buf[320];
  std::snprintf(buf, sizeof buf, "%s (%s): %zu iterations, %.3f s, kept %d/%d correspondences, mean distance %.2f mm",
                usable() ? "usable" : "NOT USABLE", to_string(termination), iterations.size(), seconds,
                final_correspondences.kept, final_correspondences.candidates, kept_mae_mm);
  return buf;
}

}  // namespace breastfit::fit
