#include "breastfit/fit/landmark_term.h"

#include "breastfit/fit/row_builder.h"
#include "breastfit/fit/sliding_landmarks.h"

namespace breastfit::fit {

double LandmarkTerm::evaluate(const TermContext& ctx, double weight, NormalEquations* eq) const {
  double cost = 0.0;
  model::PointJacobian jac;
  std::vector<double> vals;
  for (const auto& t : ctx.landmarks) {
    if (sliding_landmark_region(t.name)) continue;  // the sliding-landmark term's
    const SurfacePoint& sp = ctx.ev.model().landmarks[t.model_landmark].point;
    cost += add_surface_point_residual(ctx.ev, sp, t.position, weight * t.weight, eq, jac, vals);
  }
  return cost;
}

TermSpec landmark_term_spec() {
  return {"landmarks", "λL", 50.0, "mm²", "landmark term: squared distance per material landmark", false,
          [] { return std::unique_ptr<EnergyTerm>(new LandmarkTerm); }};
}

}  // namespace breastfit::fit
