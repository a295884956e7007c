#include "breastfit/fit/landmark_prediction.h"

#include <Eigen/Cholesky>

#include "breastfit/fit/sliding_landmarks.h"

namespace breastfit::fit {
namespace {

// H and g of the whole energy, and of the landmarks left out, at the evaluator's parameters.
struct Equations {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
};

Equations assemble(const Problem& problem, const std::vector<int>& active, const std::vector<size_t>* only) {
  NormalEquations eq(problem.evaluator().layout().num_params());
  eq.set_active(active);
  if (only)
    for (size_t i : *only) problem.evaluate_landmark(i, &eq);
  else
    problem.evaluate(&eq);
  eq.finalize();
  return {eq.H(), eq.g()};
}

// The parameters after the Newton step of the energy `all` minus `removed`. A tiny relative
// damping keeps directions the energy does not see (if any) where they are.
model::PoseParams newton_step(const Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                              const Equations& all, const Equations& removed) {
  Eigen::MatrixXd A = all.H - removed.H;
  A.diagonal() += 1e-6 * all.H.diagonal().cwiseAbs() + Eigen::VectorXd::Constant(A.rows(), 1e-9);
  const Eigen::VectorXd x = A.ldlt().solve(-(all.g - removed.g));
  const auto& layout = problem.evaluator().layout();
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(layout.num_params());
  if (x.allFinite())
    for (size_t r = 0; r < active.size(); ++r) delta[active[r]] = x[r];
  model::PoseParams out = params;
  layout.apply_increment(problem.evaluator().model(), delta, out);
  return out;
}

}  // namespace

model::PoseParams leave_out_landmarks(Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                                      const std::vector<size_t>& left_out) {
  problem.evaluator().set_params(params);
  const Equations all = assemble(problem, active, nullptr);
  const Equations removed = assemble(problem, active, &left_out);
  return newton_step(problem, params, active, all, removed);
}

std::vector<Vec3> predict_left_out_landmarks(Problem& problem, const model::PoseParams& params,
                                             const std::vector<int>& active) {
  auto& ev = problem.evaluator();
  ev.set_params(params);
  const Equations all = assemble(problem, active, nullptr);
  const auto& landmarks = problem.landmarks();
  std::vector<model::PoseParams> steps;
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const std::vector<size_t> one{i};
    steps.push_back(newton_step(problem, params, active, all, assemble(problem, active, &one)));
  }
  std::vector<Vec3> out;
  for (size_t i = 0; i < landmarks.size(); ++i) {
    ev.set_params(steps[i]);
    out.push_back(model_landmark_position(ev.model(), landmarks[i].model_landmark, ev.vertices(), steps[i]));
  }
  ev.set_params(params);
  return out;
}

Vec3 predict_left_out_relinearized(Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                                   size_t i, int steps, const Relinearization& relinearization) {
  auto& ev = problem.evaluator();
  const std::vector<size_t> one{i};
  const auto energy_without = [&] { return problem.evaluate(nullptr).total() - problem.evaluate_landmark(i, nullptr); };
  const auto recompute = [&] {
    problem.update_correspondences(relinearization.max_distance_mm, 1, relinearization.with_reverse);
    problem.update_terms(relinearization.robust_landmarks);
  };
  // The pairs at `params` (kept: found again at the end, they would be the same).
  Problem::CorrespondenceState at_params = problem.correspondence_state();
  model::PoseParams at = params;
  ev.set_params(at);
  for (int k = 0; k < steps; ++k) {
    if (k > 0) recompute();
    const double before = energy_without();
    const model::PoseParams next =
        newton_step(problem, at, active, assemble(problem, active, nullptr), assemble(problem, active, &one));
    ev.set_params(next);
    if (k > 0 && !(energy_without() < before)) break;  // went too far at these correspondences (the first is the linear one)
    at = next;
  }
  ev.set_params(at);
  const Vec3 out = model_landmark_position(ev.model(), problem.landmarks()[i].model_landmark, ev.vertices(), at);
  ev.set_params(params);
  problem.restore_correspondences(std::move(at_params));
  recompute();  // searches only when the kept pairs were not those at `params` with these arguments
  return out;
}

}  // namespace breastfit::fit
