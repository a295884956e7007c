#pragma once
/// \file The reverse data term (beyond the paper): scan sample → closest point on the posed model,
/// point-to-plane, averaged over the kept samples. It pulls the model into parts of the scan that
/// no model vertex claims (e.g. a breast larger than the template's):
///   E_R = 1/λR · 1/|S| Σ_{p∈S} w_p (n_p·(X_p(θ) − s_p))²
/// Used in the stages that move blendshapes; λR ≤ 0 disables it.
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

class ReverseTerm final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

TermSpec reverse_term_spec();

}  // namespace breastfit::fit
