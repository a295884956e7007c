#pragma once
/// \file The data term (paper eq. 8): model vertex → closest scan point, point-to-plane mixed with
/// point-to-point, robust IRLS weights, averaged over the kept correspondences:
///   E_D = 1/λD · 1/|C| Σ_{c∈C} w_c [(1−μ)(n_c·(M_i − p_c))² + μ‖M_i − p_c‖²]
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

class DataTerm final : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;
};

TermSpec data_term_spec();

}  // namespace breastfit::fit
