#include "breastfit/fit/landmark_term.h"

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/landmark_check.h"
#include "breastfit/fit/row_builder.h"
#include "breastfit/fit/sliding_landmarks.h"

namespace breastfit::fit {

void LandmarkTermBase::update_factors(const TermContext& ctx) {
  factors_.assign(ctx.landmarks.size(), 1.0);
  if (!ctx.robust_landmarks) return;
  for (size_t i = 0; i < ctx.landmarks.size(); ++i) {
    const auto& t = ctx.landmarks[i];
    const auto sp = model_point(ctx, i);
    if (!sp) continue;
    const double d = (ctx.ev.surface_point(*sp) - t.position).norm();
    factors_[i] = robust_landmark_factor(d, landmark_check_tolerance_mm(t.name, ctx.options.landmark_check_mm));
  }
}

double LandmarkTermBase::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  double cost = 0.0;
  model::PointJacobian jac;
  std::vector<double> vals;
  for (size_t i = 0; i < ctx.landmarks.size(); ++i) {
    const auto sp = model_point(ctx, i);
    if (!sp) continue;
    const auto& t = ctx.landmarks[i];
    const double factor = i < factors_.size() ? factors_[i] : 1.0;
    cost += add_surface_point_residual(ctx.ev, *sp, t.position, weight * t.weight * factor, eq, jac, vals);
  }
  return cost;
}

namespace {

class LandmarkTerm final : public LandmarkTermBase {
 public:
  void update(const TermContext& ctx) override { update_factors(ctx); }

 protected:
  std::optional<SurfacePoint> model_point(const TermContext& ctx, size_t i) const override;
};

std::optional<SurfacePoint> LandmarkTerm::model_point(const TermContext& ctx, size_t i) const {
  const auto& t = ctx.landmarks[i];
  if (sliding_landmark_region(t.name)) return std::nullopt;  // the sliding-landmark term's
  return ctx.ev.model().landmarks[t.model_landmark].point;
}

}  // namespace

TermSpec landmark_term_spec() {
  return {"landmarks", "λL", 50.0, "mm²", "landmark term: squared distance per material landmark", false,
          [] { return std::unique_ptr<EnergyTerm>(new LandmarkTerm); }};
}

}  // namespace breastfit::fit
