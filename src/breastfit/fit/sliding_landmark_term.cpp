// The landmark term for landmarks that are not material points (sliding_landmarks.h): the
// lowest breast points. Their model point is re-chosen at every outer iteration (update) as the
// breast region's lowest vertex along the posed body's vertical axis, then held fixed while the
// step is solved:
//   E_LS = 1/λLS · Σ_l w_l r_l ‖X_l(θ) − ℓ_l‖²,  X_l = the chosen model point
// Same default λ as the material landmarks (the paper's λL covers all 12).
#include "breastfit/fit/landmark_term.h"

#include <optional>

#include "breastfit/fit/sliding_landmarks.h"

namespace breastfit::fit {
namespace {

class SlidingLandmarkTerm final : public LandmarkTermBase {
 public:
  void update(const TermContext& ctx) override;

 protected:
  std::optional<SurfacePoint> model_point(const TermContext& ctx, size_t i) const override;

 private:
  std::vector<std::optional<SurfacePoint>> points_;  // per ctx.landmarks entry, chosen by update()
};

void SlidingLandmarkTerm::update(const TermContext& ctx) {
  const auto& model = ctx.ev.model();
  const Vec3 up = posed_vertical_axis(model, ctx.ev.params());
  points_.assign(ctx.landmarks.size(), std::nullopt);
  for (size_t i = 0; i < ctx.landmarks.size(); ++i)
    if (const auto region = sliding_landmark_region(ctx.landmarks[i].name))
      points_[i] = lowest_region_point(model, ctx.ev.vertices(), up, *region);
  update_factors(ctx);
}

std::optional<SurfacePoint> SlidingLandmarkTerm::model_point(const TermContext& ctx, size_t i) const {
  const auto& t = ctx.landmarks[i];
  if (!sliding_landmark_region(t.name)) return std::nullopt;  // the landmark term's
  // Before the first update (or on a model without the region): the stored landmark point.
  if (i < points_.size() && points_[i]) return points_[i];
  return ctx.ev.model().landmarks[t.model_landmark].point;
}

}  // namespace

TermSpec sliding_landmark_term_spec() {
  return {"sliding_landmarks", "λLS", 50.0, "mm²",
          "sliding landmark term: squared distance per lowest breast point (re-chosen every iteration)", false,
          [] { return std::unique_ptr<EnergyTerm>(new SlidingLandmarkTerm); }};
}

}  // namespace breastfit::fit
