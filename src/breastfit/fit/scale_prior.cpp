// Bone scale regulariser (paper eq. 5), per axis weighted by the template's stiffness:
//   E_S = 1/λS · Σ_j Σ_a k_{j,a} (s_{j,a} − 1)²     (k: Bone::scale_stiffness)
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {
namespace {

class ScalePrior final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

double ScalePrior::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  const auto& model = ctx.ev.model();
  const auto& p = ctx.ev.params();
  double cost = 0.0;
  for (int j = 0; j < model.num_bones(); ++j)
    for (int a = 0; a < 3; ++a) {
      const double r = p.bones[j].scale[a] - 1.0;
      const double w = weight * model.bones[j].scale_stiffness[a];
      cost += w * r * r;
      if (!eq) continue;
      const int idx = ctx.ev.layout().bone_offset(j) + 6 + a;
      const double one = 1.0;
      eq->add_row(&idx, &one, 1, r, w);
    }
  return cost;
}

}  // namespace

TermSpec scale_prior_spec() {
  return {"scale", "λS", 0.5, "no unit", "bone scale regulariser E_S", false,
          [] { return std::unique_ptr<EnergyTerm>(new ScalePrior); }};
}

}  // namespace breastfit::fit
