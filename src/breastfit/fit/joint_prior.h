#pragma once
/// \file Joint regulariser (paper eq. 7): each bone's rotation relative to its parent (the root's
/// relative to the global similarity), and the root bone's translation over τ:
///   E_J = 1/λJ · [ Σ_j ‖log(R_parent(j)ᵀ R_j)‖² + ‖t_root / τ‖² ]
/// τ = EnergyWeights::joint_translation_scale_mm. Child translations are tied to their parent by
/// the continuity term instead (continuity_term.h).
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

class JointPrior final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

TermSpec joint_prior_spec();

}  // namespace breastfit::fit
