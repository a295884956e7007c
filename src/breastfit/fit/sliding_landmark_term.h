#pragma once
/// \file The landmark term for landmarks that are not material points (sliding_landmarks.h): the
/// lowest breast points. Their model point is re-chosen at every outer iteration (update) as the
/// breast region's lowest vertex along the posed body's vertical axis, then held fixed while the
/// step is solved:
///   E_LS = 1/λLS · Σ_l w_l r_l ‖X_l(θ) − ℓ_l‖²,  X_l = the chosen model point
/// Same default λ as the material landmarks (the paper's λL covers all 12).
#include <optional>

#include "breastfit/fit/landmark_term.h"

namespace breastfit::fit {

class SlidingLandmarkTerm final : public LandmarkTermBase {
 public:
  void update(const TermContext& ctx) override;

 protected:
  std::optional<SurfacePoint> model_point(const TermContext& ctx, size_t i) const override;

 private:
  std::vector<std::optional<SurfacePoint>> points_;  // per ctx.landmarks entry, chosen by update()
};

TermSpec sliding_landmark_term_spec();

}  // namespace breastfit::fit
