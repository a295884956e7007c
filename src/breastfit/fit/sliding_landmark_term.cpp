#include "breastfit/fit/sliding_landmark_term.h"

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/landmark_check.h"
#include "breastfit/fit/row_builder.h"
#include "breastfit/fit/sliding_landmarks.h"

namespace breastfit::fit {

void SlidingLandmarkTerm::update(const TermContext& ctx) {
  const auto& model = ctx.ev.model();
  const Vec3 up = posed_vertical_axis(model, ctx.ev.params());
  points_.assign(ctx.landmarks.size(), std::nullopt);
  factors_.assign(ctx.landmarks.size(), 1.0);
  for (size_t i = 0; i < ctx.landmarks.size(); ++i) {
    const auto& t = ctx.landmarks[i];
    const auto region = sliding_landmark_region(t.name);
    if (!region) continue;
    points_[i] = lowest_region_point(model, ctx.ev.vertices(), up, *region);
    if (!ctx.robust_landmarks || !points_[i]) continue;
    const double d = (ctx.ev.surface_point(*points_[i]) - t.position).norm();
    factors_[i] = robust_landmark_factor(d, landmark_check_tolerance_mm(t.name, ctx.options.landmark_check_mm));
  }
}

double SlidingLandmarkTerm::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  double cost = 0.0;
  model::PointJacobian jac;
  std::vector<double> vals;
  for (size_t i = 0; i < ctx.landmarks.size(); ++i) {
    const auto& t = ctx.landmarks[i];
    if (!sliding_landmark_region(t.name)) continue;  // the landmark term's
    // Before the first update (or on a model without the region): the stored landmark point.
    const SurfacePoint& sp = i < points_.size() && points_[i] ? *points_[i] : ctx.ev.model().landmarks[t.model_landmark].point;
    const double factor = i < factors_.size() ? factors_[i] : 1.0;
    cost += add_surface_point_residual(ctx.ev, sp, t.position, weight * t.weight * factor, eq, jac, vals);
  }
  return cost;
}

TermSpec sliding_landmark_term_spec() {
  return {"sliding_landmarks", "λLS", 50.0, "mm²",
          "sliding landmark term: squared distance per lowest breast point (re-chosen every iteration)", false,
          [] { return std::unique_ptr<EnergyTerm>(new SlidingLandmarkTerm); }};
}

}  // namespace breastfit::fit
