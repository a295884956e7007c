#include "breastfit/metrics/fit_errors.h"

#include <cmath>

#include "breastfit/fit/sliding_landmarks.h"

namespace breastfit::metrics {

std::vector<double> surface_distances(const Points& V, const fit::ScanTarget& scan, bool skip_border) {
  std::vector<double> d;
  d.reserve(V.rows());
  Index hint = -1;  // neighbouring vertices have neighbouring closest points: a warm start
  for (Index i = 0; i < V.rows(); ++i) {
    const auto m = scan.closest(V.row(i).transpose(), &hint);
    if (skip_border && m.on_boundary) continue;
    d.push_back(std::sqrt(m.sq_dist));
  }
  return d;
}

LandmarkErrors landmark_errors(const model::RiggedModel& model, const Points& fitted_V,
                               const model::PoseParams& params, const std::vector<fit::LandmarkTarget>& targets) {
  LandmarkErrors out;
  for (const auto& t : targets) {
    const Vec3 p = fit::model_landmark_position(model, t.model_landmark, fitted_V, params);
    out.names.push_back(t.name);
    out.distances_mm.push_back((p - t.position).norm());
  }
  out.stats = distance_stats(out.distances_mm);
  return out;
}

}  // namespace breastfit::metrics
