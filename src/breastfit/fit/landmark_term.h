#pragma once
/// \file The landmark term (paper eq. 9) for material landmarks: squared distances between the
/// model's landmark points and the landmarks placed on the scan,
///   E_L = 1/λL · Σ_l w_l ‖L_l(θ) − ℓ_l‖²
/// (w_l: landmark_weight). The lowest breast points are not material points: sliding_landmark_term.h.
#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

class LandmarkTerm final : public EnergyTerm {
 public:
  /// Robust factors (landmark_check.h) at the current pose, when the stage asks for them.
  void update(const TermContext& ctx) override;
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;

 private:
  std::vector<double> factors_;  // per ctx.landmarks entry
};

TermSpec landmark_term_spec();

}  // namespace breastfit::fit
