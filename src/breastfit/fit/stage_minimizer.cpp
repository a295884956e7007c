#include "breastfit/fit/stage_minimizer.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "breastfit/core/timer.h"
#include "breastfit/fit/correspondence_schedule.h"
#include "breastfit/fit/lm_strategy.h"

namespace breastfit::fit {

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

namespace {

// The convergence tests of one finished iteration (only asked once the stage's threshold is final).
// `step_mm`: how far the accepted step moved the farthest model vertex.
std::optional<Termination> convergence(const SolverOptions& o, const IterationRecord& rec, bool fresh_hessian,
                                       double step_mm) {
  if (rec.gradient_max <= o.gradient_tolerance) return Termination::GradientTolerance;
  if (!rec.accepted) return fresh_hessian ? std::optional(Termination::NoFurtherDecrease) : std::nullopt;
  if (step_mm < o.vertex_tolerance_mm) return Termination::ParameterTolerance;
  const double rel = (rec.energy_before - rec.energy_after) / std::max(rec.energy_before, 1e-300);
  if (rel < o.function_tolerance) return Termination::FunctionTolerance;
  if (rec.step_norm < o.parameter_tolerance) return Termination::ParameterTolerance;
  return std::nullopt;
}

// One stage's state shared by its iterations.
class StageRun {
 public:
  StageRun(Problem& problem, const StageOptions& stage, const CorrespondenceSchedule& schedule, int data_stage)
      : problem_(problem), stage_(stage), schedule_(schedule), data_stage_(std::max(data_stage, 0)),
        options_(problem.options().solver), strategy_(options_),
        active_(active_parameters(problem.evaluator().layout(), stage, problem.options().max_blendshapes)),
        eq_(problem.evaluator().layout().num_params()),
        use_reverse_(problem.options().uses_reverse_term() && stage.blendshapes) {
    eq_.set_active(active_);
  }

  // One outer iteration from `params` (updated when a step is accepted). nullopt: go on.
  std::optional<Termination> iterate(int it, model::PoseParams& params, IterationRecord& rec) {
    auto& ev = problem_.evaluator();
    const bool rebuild = rebuild_next_ || it % options_.hessian_interval == 0;
    const bool refind = it % std::max(1, stage_.correspondence_interval) == 0;  // 0 (automatic) left: every one
    if (refind) max_dist_ = schedule_.threshold(data_stage_, it, stage_.max_iterations);
    const double max_dist = max_dist_;
    ev.set_params(params);
    relinearize(max_dist, refind);
    eq_.set_gradient_only(!rebuild);
    eq_.clear();
    const double e0 = problem_.evaluate(&eq_).total();
    eq_.finalize();
    rec = IterationRecord{};
    rec.stage = stage_.name;
    rec.iteration = it;
    rec.energy_before = rec.energy_after = e0;
    rec.max_distance_mm = max_dist;
    rec.kept = problem_.stats().kept;
    if (!std::isfinite(e0)) return Termination::NumericalFailure;
    if (rebuild) H_ = eq_.H();
    rec.gradient_max = eq_.g().size() ? eq_.g().cwiseAbs().maxCoeff() : 0.0;
    try_steps(params, e0, rec);
    rec.damping = strategy_.damping();
    rebuild_next_ = !rec.accepted;  // a stale Hessian that fails gets rebuilt
    const bool final_threshold = !stage_.use_data || schedule_.at_stage_end(data_stage_, it, stage_.max_iterations);
    if (final_threshold && it > 0) return convergence(options_, rec, rebuild, step_mm_);
    return std::nullopt;
  }

 private:
  // `refind`: the correspondences are searched again (else the stage's last pairs are kept).
  void relinearize(double max_dist, bool refind) {
    if (stage_.use_data) {
      if (refind) problem_.update_correspondences(max_dist, stage_.vertex_stride, use_reverse_);
    } else
      problem_.clear_correspondences();
    problem_.update_terms(stage_.robust_landmarks);
  }

  // Damped steps until one lowers the energy enough (or the attempts run out).
  void try_steps(model::PoseParams& params, double e0, IterationRecord& rec) {
    auto& ev = problem_.evaluator();
    const auto& layout = ev.layout();
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(layout.num_params());
    const Points before = options_.vertex_tolerance_mm > 0 ? ev.vertices() : Points();
    step_mm_ = 0;
    for (int attempt = 0; attempt < options_.max_step_attempts && !strategy_.exhausted(); ++attempt) {
      const LmStep step = strategy_.compute_step(H_, eq_.g());
      if (!step.ok) continue;
      for (size_t r = 0; r < active_.size(); ++r) delta[active_[r]] = step.x[r];
      model::PoseParams trial = params;
      layout.apply_increment(ev.model(), delta, trial);
      ev.set_params(trial);
      const double e1 = problem_.evaluate(nullptr).total();
      const double rho = (e0 - e1) / std::max(step.predicted_decrease, 1e-300);
      rec.predicted_decrease = step.predicted_decrease;
      rec.gain_ratio = rho;
      if (std::isfinite(e1) && e1 <= e0 && rho >= options_.min_gain_ratio) {
        params = trial;
        rec.accepted = true;
        rec.energy_after = e1;
        rec.step_norm = step.x.cwiseAbs().maxCoeff();
        strategy_.step_accepted(rho);
        if (before.rows() == ev.vertices().rows()) step_mm_ = (ev.vertices() - before).rowwise().norm().maxCoeff();
        return;
      }
      strategy_.step_rejected();
    }
    ev.set_params(params);
  }

  Problem& problem_;
  const StageOptions& stage_;
  const CorrespondenceSchedule& schedule_;
  int data_stage_;
  const SolverOptions& options_;
  LevenbergMarquardtStrategy strategy_;
  std::vector<int> active_;
  NormalEquations eq_;
  Eigen::MatrixXd H_;
  bool use_reverse_;  // the reverse term is used in the stages that move blendshapes
  bool rebuild_next_ = true;
  double max_dist_ = 0;  // the threshold the current pairs were found with
  double step_mm_ = 0;  // the farthest vertex move of the last accepted step (when vertex_tolerance_mm > 0)
};

}  // namespace

Termination minimize_stages(Problem& problem, const std::vector<StageOptions>& stages, model::PoseParams& params,
                            FitSummary& summary, const IterationCallback& on_iteration) {
  int num_data_stages = 0;
  for (const auto& s : stages) num_data_stages += s.max_iterations > 0 && s.use_data ? 1 : 0;
  const CorrespondenceSchedule schedule(problem.options().correspondences, num_data_stages);
  Termination last = Termination::IterationCap;
  int data_stage = -1;
  for (const auto& stage : stages) {
    if (stage.max_iterations == 0) continue;
    if (stage.use_data) ++data_stage;
    Timer stage_timer;
    StageRun run(problem, stage, schedule, data_stage);
    StageSummary ss;
    ss.name = stage.name;
    ss.termination = Termination::IterationCap;
    for (int it = 0; it < stage.max_iterations; ++it) {
      Timer it_timer;
      IterationRecord rec;
      const std::optional<Termination> end = run.iterate(it, params, rec);
      rec.seconds = it_timer.seconds();
      if (it == 0) ss.initial_energy = rec.energy_before;
      ss.iterations = it + 1;
      ss.final_energy = rec.energy_after;
      summary.iterations.push_back(rec);
      if (end) ss.termination = *end;
      if (end != Termination::NumericalFailure && on_iteration && on_iteration(rec) == CallbackResult::Abort)
        ss.termination = Termination::Aborted;
      if (ss.termination != Termination::IterationCap) break;
    }
    ss.seconds = stage_timer.seconds();
    summary.stages.push_back(ss);
    summary.timings.push_back({"stage:" + stage.name, ss.seconds});
    last = ss.termination;
    if (last == Termination::Aborted || last == Termination::NumericalFailure) break;
  }
  problem.evaluator().set_params(params);
  return last;
}

}  // namespace breastfit::fit
