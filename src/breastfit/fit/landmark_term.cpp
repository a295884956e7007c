#include "breastfit/fit/landmark_term.h"

namespace breastfit::fit {

double landmark_weight(const std::string& name) {
  if (name.rfind("midaxillary", 0) == 0) return 0.1;
  return 1.0;
}

double add_landmark_term(const model::PoseEvaluator& ev, const std::vector<LandmarkTarget>& targets, double scale,
                         NormalEquations* eq) {
  double cost = 0.0;
  model::PointJacobian jac;
  std::vector<double> vals;
  for (const auto& t : targets) {
    const SurfacePoint& sp = t.sliding_point ? *t.sliding_point : ev.model().landmarks[t.model_landmark].point;
    const Vec3 d = ev.surface_point(sp) - t.position;
    const double w = scale * t.weight;
    cost += w * d.squaredNorm();
    if (!eq) continue;
    ev.surface_point_jacobian(sp, jac);
    const int nnz = static_cast<int>(jac.params.size());
    vals.resize(nnz);
    for (int axis = 0; axis < 3; ++axis) {
      for (int k = 0; k < nnz; ++k) vals[k] = jac.columns[k][axis];
      eq->add_row(jac.params.data(), vals.data(), nnz, d[axis], w);
    }
  }
  return cost;
}

}  // namespace breastfit::fit
