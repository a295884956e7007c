#include "breastfit/metrics/plausibility.h"

#include <cmath>
#include <sstream>

namespace breastfit::metrics {
namespace {

std::string fmt(double v, int precision = 2) {
  std::ostringstream s;
  s.precision(precision);
  s << std::fixed << v;
  return s.str();
}

}  // namespace

Plausibility judge_plausibility(const model::RiggedModel& model, const model::PoseParams& params, double coverage,
                                const DistanceStats& surface, const PlausibilityOptions& o) {
  Plausibility p;
  p.global_scale = params.global.scale;
  p.coverage = coverage;
  p.surface_rmse_mm = surface.rmse;
  // A bound that is the rest value (a one-sided blendshape's 0) is where the parameter starts,
  // not an edge it was pushed to.
  const auto at_bound = [&](double v, double lo, double hi, double rest, const std::string& name) {
    ++p.bounded_parameters;
    const double tol = o.bound_tolerance * (hi - lo);
    if ((v <= lo + tol && std::abs(lo - rest) > tol) || (v >= hi - tol && std::abs(hi - rest) > tol)) {
      ++p.parameters_at_bound;
      p.at_bound.push_back(name);
    }
  };
  static constexpr const char* kAxis[3] = {"x", "y", "z"};
  for (size_t b = 0; b < model.bones.size() && b < params.bones.size(); ++b)
    for (int a = 0; a < 3; ++a)
      if (model.bones[b].scale_hi[a] > model.bones[b].scale_lo[a])
        at_bound(params.bones[b].scale[a], model.bones[b].scale_lo[a], model.bones[b].scale_hi[a], 1.0,
                 model.bones[b].name + ".scale_" + kAxis[a]);
  for (size_t k = 0; k < model.blendshapes.size() && static_cast<Eigen::Index>(k) < params.alpha.size(); ++k)
    if (model.blendshapes[k].hi > model.blendshapes[k].lo)
      at_bound(params.alpha[static_cast<Eigen::Index>(k)], model.blendshapes[k].lo, model.blendshapes[k].hi, 0.0,
               model.blendshapes[k].name);

  if (!(p.global_scale >= o.min_global_scale && p.global_scale <= o.max_global_scale))
    p.problems.push_back("the fitted torso is " + fmt(p.global_scale) + " times the template's size (plausible " +
                         fmt(o.min_global_scale, 1) + "-" + fmt(o.max_global_scale, 1) +
                         "): not an adult torso, or wrong units");
  if (p.bounded_parameters > 0 &&
      p.parameters_at_bound > o.max_at_bound_fraction * static_cast<double>(p.bounded_parameters)) {
    std::string names;
    for (size_t i = 0; i < p.at_bound.size() && i < 6; ++i) names += (i ? ", " : "") + p.at_bound[i];
    if (p.at_bound.size() > 6) names += ", ...";
    p.problems.push_back(std::to_string(p.parameters_at_bound) + " of " + std::to_string(p.bounded_parameters) +
                         " shape parameters ended at a bound (" + names + "): the shape space was pushed to its edge");
  }
  if (coverage < o.min_coverage)
    p.problems.push_back("the scan covers " + fmt(100 * coverage, 0) + " % of the fitted model (plausible from " +
                         fmt(100 * o.min_coverage, 0) + " %): the scan is not this torso's surface, or the fit is off it");
  if (surface.n > 0 && surface.rmse > o.max_surface_rmse_mm)
    p.problems.push_back("surface error RMSE " + fmt(surface.rmse) + " mm over the covered part (plausible up to " +
                         fmt(o.max_surface_rmse_mm, 1) + " mm): the model follows the scan in places only");
  p.plausible = p.problems.empty();
  return p;
}

}  // namespace breastfit::metrics
