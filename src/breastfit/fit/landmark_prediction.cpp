#include "breastfit/fit/landmark_prediction.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>

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

// A factor U (n × k, k the rank) of the positive semi-definite H = U Uᵀ of a few residual rows:
// pivoted Cholesky, stopped when what is left of the diagonal is rounding.
Eigen::MatrixXd low_rank_factor(const Eigen::MatrixXd& H) {
  const Eigen::Index n = H.rows();
  Eigen::VectorXd d = H.diagonal();
  const double floor = 1e-12 * std::max(d.maxCoeff(), 0.0);
  Eigen::MatrixXd U(n, 0);
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::Index j = 0;
    if (!(d.maxCoeff(&j) > floor) || !(d[j] > 0)) break;
    Eigen::VectorXd u = H.col(j) - U * U.row(j).transpose();
    u /= std::sqrt(u[j]);
    d -= u.cwiseAbs2();
    d[j] = 0;
    U.conservativeResize(Eigen::NoChange, k + 1);
    U.col(k) = u;
  }
  return U;
}

// The Newton steps of the energy `all` minus a few residual rows `removed`, for many `removed`
// from one factorisation: A = H + damping is factored once, A − H_removed solved by the
// Sherman–Morrison–Woodbury identity with H_removed = U Uᵀ of rank k (a landmark: 3 or fewer),
//   (A − U Uᵀ)⁻¹ b = y + Z (I − Uᵀ Z)⁻¹ Uᵀ y,  y = A⁻¹ b, Z = A⁻¹ U,
// k + 1 triangular solves instead of a factorisation per landmark. The tiny relative damping
// keeps directions the energy does not see (if any) where they are.
class LeaveOutSolver {
 public:
  explicit LeaveOutSolver(const Equations& all) : g_(all.g) {
    Eigen::MatrixXd A = all.H;
    A.diagonal() += 1e-6 * all.H.diagonal().cwiseAbs() + Eigen::VectorXd::Constant(A.rows(), 1e-9);
    ldlt_.compute(A);
  }
  // The step −(A − H_removed)⁻¹ (g − g_removed).
  Eigen::VectorXd step(const Equations& removed) const {
    const Eigen::VectorXd y = ldlt_.solve(-(g_ - removed.g));
    const Eigen::MatrixXd U = low_rank_factor(removed.H);
    if (U.cols() == 0) return y;
    const Eigen::MatrixXd Z = ldlt_.solve(U);
    Eigen::MatrixXd C = -U.transpose() * Z;
    C.diagonal().array() += 1.0;
    return y + Z * C.partialPivLu().solve(U.transpose() * y);
  }

 private:
  Eigen::VectorXd g_;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
};

// The parameters after the Newton step of the energy `all` (factored in `solver`) minus `removed`.
model::PoseParams newton_step(const Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                              const LeaveOutSolver& solver, const Equations& removed) {
  const Eigen::VectorXd x = solver.step(removed);
  const auto& layout = problem.evaluator().layout();
  Eigen::VectorXd delta = Eigen::VectorXd::Zero(layout.num_params());
  if (x.allFinite())
    for (size_t r = 0; r < active.size(); ++r) delta[active[r]] = x[r];
  model::PoseParams out = params;
  layout.apply_increment(problem.evaluator().model(), delta, out);
  return out;
}

// The rows of the posed mesh model_landmark_position reads for `landmark`, ascending: its surface
// point's corners and, for a sliding landmark (sliding_landmarks.h), its region's vertices and the
// corners of every face touching them (lowest_region_point's face is one of those).
std::vector<Index> rows_read(const model::RiggedModel& model, int landmark) {
  const Triangles& F = model.rest.F;
  const auto& lm = model.landmarks[landmark];
  std::vector<char> read(static_cast<size_t>(model.num_vertices()), 0);
  const auto add_face = [&](Index f) {
    for (int c = 0; c < 3; ++c) read[static_cast<size_t>(F(f, c))] = 1;
  };
  if (lm.point.face >= 0 && lm.point.face < F.rows()) add_face(lm.point.face);
  const auto region = sliding_landmark_region(lm.name);
  if (const auto r = region ? model.region_index(*region) : std::nullopt) {
    std::vector<char> in_region(read.size(), 0);
    for (Index v : model.regions[*r].vertices) in_region[static_cast<size_t>(v)] = read[static_cast<size_t>(v)] = 1;
    for (Index f = 0; f < F.rows(); ++f)
      if (in_region[F(f, 0)] || in_region[F(f, 1)] || in_region[F(f, 2)]) add_face(f);
  }
  std::vector<Index> rows;
  for (size_t v = 0; v < read.size(); ++v)
    if (read[v]) rows.push_back(static_cast<Index>(v));
  return rows;
}

}  // namespace

model::PoseParams leave_out_landmarks(Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                                      const std::vector<size_t>& left_out) {
  problem.evaluator().set_params(params);
  const LeaveOutSolver solver(assemble(problem, active, nullptr));
  return newton_step(problem, params, active, solver, assemble(problem, active, &left_out));
}

std::vector<Vec3> predict_left_out_landmarks(Problem& problem, const model::PoseParams& params,
                                             const std::vector<int>& active, std::vector<model::PoseParams>* steps_out) {
  auto& ev = problem.evaluator();
  ev.set_params(params);
  const LeaveOutSolver solver(assemble(problem, active, nullptr));
  const auto& landmarks = problem.landmarks();
  std::vector<model::PoseParams> steps;
  for (size_t i = 0; i < landmarks.size(); ++i) {
    const std::vector<size_t> one{i};
    steps.push_back(newton_step(problem, params, active, solver, assemble(problem, active, &one)));
  }
  // Each step's landmark from the few vertices it reads, posed into a copy of the mesh at
  // `params` (pose_rows: the bits of posing the whole mesh; the evaluator stays at `params`).
  std::vector<Vec3> out;
  Points V = ev.vertices();
  for (size_t i = 0; i < landmarks.size(); ++i) {
    ev.pose_rows(steps[i], rows_read(ev.model(), landmarks[i].model_landmark), V);
    out.push_back(model_landmark_position(ev.model(), landmarks[i].model_landmark, V, steps[i]));
  }
  if (steps_out) *steps_out = std::move(steps);
  return out;
}

Vec3 predict_left_out_relinearized(Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                                   size_t i, int steps, const Relinearization& relinearization,
                                   const model::PoseParams* linear_step) {
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
    if (k == 0 && linear_step) {
      at = *linear_step;
      ev.set_params(at);
      continue;
    }
    if (k > 0) recompute();
    const double before = k > 0 ? energy_without() : 0.0;  // the first step is taken whatever it does
    const model::PoseParams next =
        newton_step(problem, at, active, LeaveOutSolver(assemble(problem, active, nullptr)), assemble(problem, active, &one));
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
