#include "breastfit/fit/surface_term.h"

namespace breastfit::fit {
namespace {

// Scratch space for one sparse row (reused: no allocation in the loop after the first call).
struct RowScratch {
  model::PointJacobian jac;
  std::vector<double> vals;
};

void add_point_rows(const model::PointJacobian& jac, const Vec3& d, const Vec3& n, double w_plane, double w_point,
                    NormalEquations& eq, std::vector<double>& vals) {
  const int nnz = static_cast<int>(jac.params.size());
  vals.resize(nnz);
  if (w_plane > 0) {
    for (int k = 0; k < nnz; ++k) vals[k] = n.dot(jac.columns[k]);
    eq.add_row(jac.params.data(), vals.data(), nnz, n.dot(d), w_plane);
  }
  if (w_point > 0) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int k = 0; k < nnz; ++k) vals[k] = jac.columns[k][axis];
      eq.add_row(jac.params.data(), vals.data(), nnz, d[axis], w_point);
    }
  }
}

}  // namespace

double add_data_term(const model::PoseEvaluator& ev, const std::vector<Correspondence>& pairs, double mu,
                     double scale, NormalEquations* eq) {
  const Points& M = ev.vertices();
  double cost = 0.0;
  RowScratch s;
  for (const auto& c : pairs) {
    const Vec3 d = M.row(c.vertex).transpose() - c.target;
    const double w_plane = scale * c.weight * (1.0 - mu);
    const double w_point = scale * c.weight * mu;
    const double r = c.normal.dot(d);
    cost += w_plane * r * r + w_point * d.squaredNorm();
    if (eq) {
      ev.vertex_jacobian(c.vertex, s.jac);
      add_point_rows(s.jac, d, c.normal, w_plane, w_point, *eq, s.vals);
    }
  }
  return cost;
}

double add_reverse_term(const model::PoseEvaluator& ev, const std::vector<ReverseCorrespondence>& pairs,
                        double scale, NormalEquations* eq) {
  double cost = 0.0;
  RowScratch s;
  const Triangles& F = ev.model().rest.F;
  for (const auto& c : pairs) {
    const Vec3 d = ev.surface_point(c.model_point) - c.source;
    const double w = scale * c.weight;
    const double r = c.normal.dot(d);
    cost += w * r * r;
    if (!eq) continue;
    // The row is Σ_corners bary_c · nᵀ ∂M_c/∂θ: assembled corner by corner (no merging).
    eq->begin_row(r, w);
    for (int corner = 0; corner < 3; ++corner) {
      ev.vertex_jacobian(F(c.model_point.face, corner), s.jac);
      const int nnz = static_cast<int>(s.jac.params.size());
      s.vals.resize(nnz);
      for (int k = 0; k < nnz; ++k) s.vals[k] = c.normal.dot(s.jac.columns[k]);
      eq->add_to_row(s.jac.params.data(), s.vals.data(), nnz, c.model_point.bary[corner]);
    }
    eq->end_row();
  }
  return cost;
}

}  // namespace breastfit::fit
