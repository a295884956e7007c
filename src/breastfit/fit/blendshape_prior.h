#pragma once
/// \file Blendshape regulariser (paper eq. 6, squared so that it is smooth at 0):
///   E_BS = 1/λBS · Σ_k α_k²
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

class BlendshapePrior final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

TermSpec blendshape_prior_spec();

}  // namespace breastfit::fit
