// Blendshape regulariser (paper eq. 6, squared so that it is smooth at 0):
//   E_BS = 1/λBS · Σ_k α_k²
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {
namespace {

class BlendshapePrior final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

double BlendshapePrior::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  const auto& alpha = ctx.ev.params().alpha;
  double cost = 0.0;
  for (int k = 0; k < ctx.ev.model().num_blendshapes(); ++k) {
    const double a = alpha[k];
    cost += weight * a * a;
    if (!eq) continue;
    const int idx = ctx.ev.layout().blendshape_offset(k);
    const double one = 1.0;
    eq->add_row(&idx, &one, 1, a, weight);
  }
  return cost;
}

}  // namespace

TermSpec blendshape_prior_spec() {
  return {"blendshapes", "λBS", 10.0, "no unit", "blendshape regulariser E_BS", false,
          [] { return std::unique_ptr<EnergyTerm>(new BlendshapePrior); }};
}

}  // namespace breastfit::fit
