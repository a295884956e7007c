#include "breastfit/fit/row_builder.h"

namespace breastfit::fit {

void add_point_rows(const model::PointJacobian& jac, const Vec3& d, double w, NormalEquations& eq,
                    std::vector<double>& vals) {
  const int nnz = static_cast<int>(jac.params.size());
  vals.resize(nnz);
  for (int axis = 0; axis < 3; ++axis) {
    for (int k = 0; k < nnz; ++k) vals[k] = jac.columns[k][axis];
    eq.add_row(jac.params.data(), vals.data(), nnz, d[axis], w);
  }
}

double add_surface_point_residual(const model::PoseEvaluator& ev, const SurfacePoint& point, const Vec3& target,
                                  double w, NormalEquations* eq, model::PointJacobian& jac,
                                  std::vector<double>& vals) {
  const Vec3 d = ev.surface_point(point) - target;
  if (eq) {
    ev.surface_point_jacobian(point, jac);
    add_point_rows(jac, d, w, *eq, vals);
  }
  return w * d.squaredNorm();
}

void add_plane_row(const model::PointJacobian& jac, const Vec3& d, const Vec3& n, double w, NormalEquations& eq,
                   std::vector<double>& vals) {
  const int nnz = static_cast<int>(jac.params.size());
  vals.resize(nnz);
  for (int k = 0; k < nnz; ++k) vals[k] = n.dot(jac.columns[k]);
  eq.add_row(jac.params.data(), vals.data(), nnz, n.dot(d), w);
}

}  // namespace breastfit::fit
