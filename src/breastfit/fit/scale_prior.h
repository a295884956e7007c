#pragma once
/// \file Bone scale regulariser (paper eq. 5), per axis weighted by the template's stiffness:
///   E_S = 1/λS · Σ_j Σ_a k_{j,a} (s_{j,a} − 1)²     (k: Bone::scale_stiffness)
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

class ScalePrior final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

TermSpec scale_prior_spec();

}  // namespace breastfit::fit
