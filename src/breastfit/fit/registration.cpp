#include "breastfit/fit/registration.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "breastfit/core/errors.h"
#include "breastfit/core/timer.h"
#include "breastfit/fit/initialization.h"
#include "breastfit/fit/lm_solver.h"
#include "breastfit/fit/problem.h"
#include "breastfit/mesh/landmark_names.h"

namespace breastfit::fit {
namespace {

std::string fmt(double v, int digits = 1) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

}  // namespace

std::vector<LandmarkTarget> match_landmarks(const model::RiggedModel& model,
                                            const std::vector<std::pair<std::string, Vec3>>& landmarks_mm) {
  std::vector<LandmarkTarget> out;
  std::set<std::string> seen;
  for (const auto& [name, pos] : landmarks_mm) {
    if (!seen.insert(name).second) throw InvalidInput("landmark '" + name + "' is given twice");
    if (!pos.allFinite()) throw InvalidInput("landmark '" + name + "' has a non-finite position");
    const auto idx = model.landmark_index(name);
    if (!idx)
      throw InvalidInput("landmark '" + name + "' is not a landmark of template '" + model.name +
                         "' (expected: " + landmark_name_list() + ")");
    out.push_back({name, *idx, pos, landmark_weight(name)});
  }
  // The paper's order (kLandmarkNames), so that "the first n landmarks" is reproducible.
  std::stable_sort(out.begin(), out.end(), [](const LandmarkTarget& a, const LandmarkTarget& b) {
    return landmark_index(a.name).value_or(99) < landmark_index(b.name).value_or(99);
  });
  return out;
}

FitResult register_template(const model::RiggedModel& model, ScanTarget& scan, std::vector<LandmarkTarget> landmarks,
                            const FitOptions& options, const IterationCallback& on_iteration) {
  options.validate();
  Timer timer;
  FitResult result;
  FitSummary& summary = result.summary;

  if (!options.use_landmarks) landmarks.clear();
  if (options.max_landmarks >= 0 && static_cast<int>(landmarks.size()) > options.max_landmarks)
    landmarks.resize(options.max_landmarks);

  model::PoseParams params = model::PoseParams::identity(model);
  if (landmarks.size() >= 3) {
    const LandmarkInitialization init = initialize_from_landmarks(model, landmarks);
    params.global = init.similarity;
    summary.initialization = "landmarks";
    if (init.swapped)
      summary.warnings.push_back("the landmarks' _R/_L labels look swapped (RMS " + fmt(init.swapped_rms_mm) +
                                 " mm as given, " + fmt(init.rms_mm) + " mm with R and L exchanged): corrected");
  } else {
    if (!landmarks.empty())
      summary.warnings.push_back("fewer than 3 landmarks: initialised without landmarks; the " +
                                 std::to_string(landmarks.size()) + " given are used in the fit");
    params.global = initialize_without_landmarks(model, scan, options);
    summary.initialization = "landmark-free";
    summary.warnings.push_back(
        "registered without landmarks: the template's orientation on the scan comes from its shape alone "
        "and can be wrong (on the benchmark: landmark errors of 12-38 mm, one case upside down); check the "
        "landmarks and drawings before use, or give at least 3 landmarks");
  }
  summary.landmarks_used = static_cast<int>(landmarks.size());

  Problem problem(model, scan, options, landmarks);
  problem.evaluator().set_params(params);
  problem.orient_scan_normals(options.correspondences.max_distance_start_mm);
  initialize_arms(model, scan, params);

  std::vector<StageOptions> stages;
  if (landmarks.size() >= 3) stages.push_back(options.landmark_pose);
  for (const auto& s : {options.rigid, options.pose, options.shape, options.refine}) stages.push_back(s);
  const bool ok = solve_stages(problem, stages, params, summary, on_iteration);

  // Final state: every vertex at the final threshold.
  const bool use_reverse = options.weights.lambda_reverse > 0 && options.correspondences.reverse_samples > 0;
  problem.evaluator().set_params(params);
  problem.update_correspondences(options.correspondences.max_distance_end_mm, 1, use_reverse);
  summary.final_energy = problem.evaluate(nullptr);
  summary.final_correspondences = problem.stats();
  summary.final_reverse_correspondences = problem.reverse_stats();
  summary.kept_mae_mm = problem.kept_mae_mm();

  const auto& st = problem.stats();
  const double kept_fraction = st.candidates > 0 ? static_cast<double>(st.kept) / st.candidates : 0.0;
  const Termination last = summary.stages.empty() ? Termination::MaxIterations : summary.stages.back().termination;
  if (!ok || !std::isfinite(summary.final_energy.total())) {
    summary.termination = Termination::NumericalFailure;
    summary.message = "numerical failure: the energy became non-finite";
  } else if (kept_fraction < options.min_kept_fraction) {
    summary.termination = Termination::NotUsable;
    summary.message = "not converged: only " + fmt(100 * kept_fraction, 0) + "% of the template lies within " +
                      fmt(options.correspondences.max_distance_end_mm) +
                      " mm of the scan (is this an upper-torso scan? are the landmarks right?)";
  } else if (summary.kept_mae_mm > options.max_surface_mae_mm) {
    summary.termination = Termination::NotUsable;
    summary.message = "not converged: mean template-to-scan distance " + fmt(summary.kept_mae_mm, 2) +
                      " mm exceeds " + fmt(options.max_surface_mae_mm) + " mm";
  } else {
    summary.termination = last;
    summary.message = std::string(to_string(last)) + " after " + std::to_string(summary.iterations.size()) +
                      " iterations";
  }
  result.params = params;
  result.vertices = problem.evaluator().vertices();
  result.model_vertices = result.vertices;
  if (options.detail.enabled && summary.usable()) {
    const SurfaceDetail d =
        fit_surface_detail(result.vertices, model.rest.F, scan, options.correspondences, options.detail);
    result.vertices = d.vertices;
    result.detail_offsets = d.offsets;
    summary.detail = {true, d.kept, d.mean_abs_mm, d.max_abs_mm};
  }
  result.landmarks = landmarks;
  summary.seconds = timer.seconds();
  return result;
}

}  // namespace breastfit::fit
