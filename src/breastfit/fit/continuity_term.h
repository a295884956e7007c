#pragma once
/// \file Joint continuity (stiff penalty): the joint point c_j of every non-root bone, moved by the
/// bone and by its parent, stays in one place:
///   E_C = 1/λC · Σ_{j≠root} ‖P_parent(j)(c_j) − P_j(c_j)‖²
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

class ContinuityTerm final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

TermSpec continuity_term_spec();

}  // namespace breastfit::fit
