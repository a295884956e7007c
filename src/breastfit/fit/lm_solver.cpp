#include "breastfit/fit/lm_solver.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace breastfit::fit {
namespace {

std::vector<int> active_parameters(const model::ParamLayout& layout, const StageOptions& stage, int max_shapes) {
  std::vector<int> active;
  if (stage.global)
    for (int i = 0; i < model::ParamLayout::kGlobalSize; ++i) active.push_back(i);
  if (stage.bones)
    for (int j = 0; j < layout.num_bones(); ++j)
      for (int k = 0; k < model::ParamLayout::kBoneSize; ++k) active.push_back(layout.bone_offset(j) + k);
  if (stage.blendshapes) {
    const int n = max_shapes < 0 ? layout.num_blendshapes() : std::min(max_shapes, layout.num_blendshapes());
    for (int k = 0; k < n; ++k) active.push_back(layout.blendshape_offset(k));
  }
  return active;
}

// Correspondence distance threshold: stage k of n decays geometrically from
// start·(end/start)^(k/n) to start·(end/start)^((k+1)/n) over the first half of its iterations.
double threshold_at(const CorrespondenceOptions& c, int stage, int num_stages, int it, int max_it) {
  const double ratio = c.max_distance_end_mm / c.max_distance_start_mm;
  const double ramp = std::max(1, max_it / 2);
  const double t = (stage + std::min(1.0, it / ramp)) / num_stages;
  return c.max_distance_start_mm * std::pow(ratio, t);
}

}  // namespace

bool solve_stages(Problem& problem, const std::vector<StageOptions>& stages, model::PoseParams& params,
                  FitSummary& summary, const IterationCallback& on_iteration) {
  const FitOptions& options = problem.options();
  auto& ev = problem.evaluator();
  const auto& model = ev.model();
  const model::ParamLayout& layout = ev.layout();
  int num_stages = 0;
  for (const auto& s : stages) num_stages += s.max_iterations > 0 && s.use_data ? 1 : 0;
  const bool use_reverse = options.weights.lambda_reverse > 0 && options.correspondences.reverse_samples > 0;

  NormalEquations eq(layout.num_params());
  int stage_index = -1;
  for (const auto& stage : stages) {
    if (stage.max_iterations == 0) continue;
    if (stage.use_data) ++stage_index;
    const int schedule_index = std::max(stage_index, 0);
    StageSummary ss;
    ss.name = stage.name;
    ss.termination = Termination::MaxIterations;
    const std::vector<int> active = active_parameters(layout, stage, options.max_blendshapes);
    const int na = static_cast<int>(active.size());
    eq.set_active(active);
    double damping = options.initial_damping;
    Eigen::MatrixXd A(na, na), Ad(na, na);
    Eigen::VectorXd b(na);
    const double stage_end = threshold_at(options.correspondences, schedule_index + 1, num_stages, 0, 1);
    bool rebuild_next = true;
    for (int it = 0; it < stage.max_iterations; ++it) {
      const bool rebuild = rebuild_next || it % options.hessian_interval == 0;
      eq.set_gradient_only(!rebuild);
      const double max_dist = threshold_at(options.correspondences, schedule_index, num_stages, it, stage.max_iterations);
      const bool final_threshold = max_dist <= stage_end * 1.0001;
      ev.set_params(params);
      problem.update_sliding_landmarks();
      if (stage.use_data)
        problem.update_correspondences(max_dist, stage.vertex_stride, use_reverse && stage.blendshapes);
      else
        problem.clear_correspondences();
      eq.clear();
      const double e0 = problem.evaluate(&eq).total();
      eq.finalize();
      if (it == 0) ss.initial_energy = e0;
      if (!std::isfinite(e0)) {
        ss.termination = Termination::NumericalFailure;
        summary.stages.push_back(ss);
        return false;
      }
      if (rebuild) A = eq.H();
      b = -eq.g();
      IterationRecord rec;
      rec.stage = stage.name;
      rec.iteration = it;
      rec.energy_before = e0;
      rec.energy_after = e0;
      rec.max_distance_mm = max_dist;
      rec.kept = problem.stats().kept;
      model::PoseParams trial;
      Eigen::VectorXd delta = Eigen::VectorXd::Zero(layout.num_params());
      for (int attempt = 0; attempt < 8; ++attempt) {
        Ad = A;
        for (int r = 0; r < na; ++r) Ad(r, r) += damping * std::max(A(r, r), 1e-9) + 1e-12;
        Eigen::LDLT<Eigen::MatrixXd> ldlt(Ad);
        const Eigen::VectorXd x = ldlt.solve(b);
        if (ldlt.info() != Eigen::Success || !x.allFinite()) {
          damping *= 10.0;
          continue;
        }
        for (int r = 0; r < na; ++r) delta[active[r]] = x[r];
        trial = params;
        layout.apply_increment(model, delta, trial);
        ev.set_params(trial);
        const double e1 = problem.evaluate(nullptr).total();
        if (std::isfinite(e1) && e1 <= e0) {
          params = trial;
          rec.accepted = true;
          rec.energy_after = e1;
          rec.step_norm = x.cwiseAbs().maxCoeff();
          damping = std::max(damping / 3.0, 1e-9);
          break;
        }
        damping *= 5.0;
      }
      rec.damping = damping;
      rebuild_next = !rec.accepted;  // a stale Hessian that fails gets rebuilt
      summary.iterations.push_back(rec);
      if (on_iteration) on_iteration(rec);
      ss.iterations = it + 1;
      ss.final_energy = rec.energy_after;
      const double rel = (rec.energy_before - rec.energy_after) / std::max(rec.energy_before, 1e-300);
      if ((final_threshold || !stage.use_data) && it > 0) {
        if ((!rec.accepted && rebuild) || (rec.accepted && rel < options.function_tolerance)) {
          ss.termination = Termination::Converged;
          break;
        }
        if (rec.step_norm < options.step_tolerance) {
          ss.termination = Termination::StepTooSmall;
          break;
        }
      }
    }
    summary.stages.push_back(ss);
  }
  ev.set_params(params);
  return true;
}

}  // namespace breastfit::fit
