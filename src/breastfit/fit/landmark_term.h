#pragma once
/// \file What the two landmark terms (paper eq. 9) share: squared distances between the model's
/// landmark points and the landmarks placed on the scan,
///   E_L = 1/λL · Σ_l w_l r_l ‖X_l(θ) − ℓ_l‖²
/// (w_l: landmark_weight; r_l: the robust factor of landmark_check.h in the stages that ask for it).
/// landmark_term.cpp: the material landmarks (X_l = the template's stored surface point);
/// sliding_landmark_term.cpp: the lowest breast points, which are not material points.
#include <optional>
#include <vector>

#include "breastfit/fit/energy_term.h"

namespace breastfit::fit {

/// What both landmark terms share: the residual loop and the robust factors. A derived term says
/// which model point stands for input landmark i (nullopt: not this term's landmark).
class LandmarkTermBase : public EnergyTerm {
 public:
  double evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const override;

 protected:
  virtual std::optional<SurfacePoint> model_point(const TermContext& ctx, size_t i) const = 0;
  /// Robust factors at the current pose (all 1 unless ctx.robust_landmarks).
  void update_factors(const TermContext& ctx);

 private:
  std::vector<double> factors_;  // per ctx.landmarks entry
};

}  // namespace breastfit::fit
