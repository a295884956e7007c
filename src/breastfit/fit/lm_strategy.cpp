#include "breastfit/fit/lm_strategy.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace breastfit::fit {

LevenbergMarquardtStrategy::LevenbergMarquardtStrategy(const SolverOptions& options) : options_(options) { reset(); }

void LevenbergMarquardtStrategy::reset() { mu_ = options_.initial_damping; }

LmStep LevenbergMarquardtStrategy::compute_step(const Eigen::MatrixXd& H, const Eigen::VectorXd& g) {
  LmStep step;
  if (!H.allFinite() || !g.allFinite()) {
    step_rejected();
    return step;
  }
  const Eigen::Index n = H.rows();
  damped_ = H;
  // Marquardt's scaling by diag(H), floored so that parameters no row touches stay regular.
  for (Eigen::Index r = 0; r < n; ++r) damped_(r, r) += mu_ * std::max(H(r, r), 1e-9) + 1e-12;
  Eigen::LDLT<Eigen::Ref<Eigen::MatrixXd>> ldlt(damped_);  // in place: factorised where it was damped (no copy)
  step.x = ldlt.solve(-g);
  if (ldlt.info() != Eigen::Success || !step.x.allFinite()) {
    step_rejected();
    return step;
  }
  step.predicted_decrease = -(2.0 * g.dot(step.x) + step.x.dot(H * step.x));
  step.ok = std::isfinite(step.predicted_decrease);
  if (!step.ok) step_rejected();
  return step;
}

void LevenbergMarquardtStrategy::step_accepted(double rho) {
  if (rho >= options_.good_gain_ratio)
    mu_ = std::clamp(mu_ / options_.damping_decrease, options_.min_damping, options_.max_damping);
}

void LevenbergMarquardtStrategy::step_rejected() {
  mu_ = std::min(mu_ * options_.damping_increase, options_.max_damping);
}

}  // namespace breastfit::fit
