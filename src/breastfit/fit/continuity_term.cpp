// Joint continuity (stiff penalty): the joint point c_j of every non-root bone, moved by the
// bone and by its parent, stays in one place:
//   E_C = 1/λC · Σ_{j≠root} ‖P_parent(j)(c_j) − P_j(c_j)‖²
#include "breastfit/fit/energy_term.h"

#include "breastfit/fit/row_builder.h"

namespace breastfit::fit {
namespace {

class ContinuityTerm final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};
namespace {

// a − b as one sparse Jacobian (columns of shared parameters merged).
model::PointJacobian difference(const model::PointJacobian& a, const model::PointJacobian& b) {
  model::PointJacobian out = a;
  for (size_t k = 0; k < b.params.size(); ++k) {
    bool found = false;
    for (size_t m = 0; m < out.params.size(); ++m)
      if (out.params[m] == b.params[k]) {
        out.columns[m] -= b.columns[k];
        found = true;
      }
    if (!found) {
      out.params.push_back(b.params[k]);
      out.columns.push_back(-b.columns[k]);
    }
  }
  return out;
}

}  // namespace

double ContinuityTerm::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  const auto& model = ctx.ev.model();
  double cost = 0.0;
  model::PointJacobian a, b;
  std::vector<double> vals;
  for (int j = 0; j < model.num_bones(); ++j) {
    const auto parent = model.bones[j].parent;
    if (!parent) continue;
    const Vec3 r = ctx.ev.pivot_moved_by(j, j) - ctx.ev.pivot_moved_by(j, *parent);
    cost += weight * r.squaredNorm();
    if (!eq) continue;
    ctx.ev.pivot_moved_by_jacobian(j, j, a);
    ctx.ev.pivot_moved_by_jacobian(j, *parent, b);
    add_point_rows(difference(a, b), r, weight, *eq, vals);
  }
  return cost;
}

}  // namespace

TermSpec continuity_term_spec() {
  return {"continuity", "λC", 0.05, "mm²", "joint continuity penalty (stiff)", false,
          [] { return std::unique_ptr<EnergyTerm>(new ContinuityTerm); }};
}

}  // namespace breastfit::fit
