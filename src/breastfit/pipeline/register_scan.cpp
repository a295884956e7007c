#include "breastfit/pipeline/register_scan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "breastfit/core/errors.h"
#include "breastfit/core/task_queue.h"
#include "breastfit/core/timer.h"
#include "breastfit/fit/parallel_chunks.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/model/template_library.h"
#include "breastfit/pipeline/landmark_frame_check.h"
#include "breastfit/fit/sliding_landmarks.h"
#include "breastfit/mesh/landmark_names.h"

namespace breastfit::pipeline {
namespace {

Markups evaluate_landmarks(const model::RiggedModel& model, const Points& V, const model::PoseParams& params) {
  Markups m;
  for (int l = 0; l < static_cast<int>(model.landmarks.size()); ++l)
    m.points.push_back({model.landmarks[l].name, fit::model_landmark_position(model, l, V, params)});
  return m;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

}  // namespace

std::vector<fit::LandmarkTarget> initialization_landmarks(std::vector<fit::LandmarkTarget> targets,
                                                          const fit::FitOptions& options) {
  return fit::select_landmarks(std::move(targets), options);
}

PreparedTarget prepare_target(const TriangleMesh& scan, const std::string& scan_name,
                              std::optional<mesh::Units> units, const fit::FitOptions& options,
                              const std::function<void(const PreparedScan&)>& before_index) {
  return prepare_target(TriangleMesh(scan), scan_name, units, options, before_index);
}

PreparedTarget prepare_target(TriangleMesh&& scan, const std::string& scan_name, std::optional<mesh::Units> units,
                              const fit::FitOptions& options,
                              const std::function<void(const PreparedScan&)>& before_index) {
  PreparedTarget t;
  t.scan_name = scan_name;
  Timer phase;
  t.scan = prepare_scan(std::move(scan), scan_name, units);
  t.timings.push_back({"scan_preparation", phase.seconds()});
  if (before_index) before_index(t.scan);
  phase.reset();
  t.target = std::make_unique<fit::ScanTarget>(t.scan.mesh_mm, options.correspondences.reverse_samples,
                                                options.threads);
  t.timings.push_back({"index_build", phase.seconds()});
  return t;
}

RegisterResult register_scan(const RegisterRequest& req, const fit::IterationCallback& on_iteration) {
  PreparedTarget target = prepare_target(req.scan, req.scan_name, req.units, req.options);
  RegisterResult out = register_prepared(req, target, on_iteration);
  out.time_s += target.timings.back().seconds;  // from scan in memory: the index build included
  return out;
}

RegisterResult register_prepared(const RegisterRequest& req, PreparedTarget& target,
                                 const fit::IterationCallback& on_iteration, const SurfaceCallback& on_surface) {
  const std::shared_ptr<const model::RiggedModel> model_ptr =
      req.model ? req.model : std::make_shared<const model::RiggedModel>(model::load_default_template());
  const model::RiggedModel& model = *model_ptr;
  if (model.landmarks.empty() && model.drawings.empty())
    throw InvalidInput("the template '" + model.name +
                       "' has no landmarks and no drawings: not a breastfit torso template (docs/TEMPLATE_FORMAT.md)");
  RegisterResult out;
  out.scan_name = target.scan_name;
  Timer phase;
  if (target.single_use)
    out.scan = std::move(target.scan);  // not copied: the caller has no further fit on this target
  else
    out.scan = target.scan;
  out.warnings = out.scan.warnings;
  fit::FitOptions options = req.options;
  if (out.scan.was_point_cloud) options.correspondences.reject_boundary = false;
  if (req.provenance) {
    out.provenance = req.provenance;
    out.provenance->options = options;
  }

  std::vector<std::pair<std::string, Vec3>> landmarks_mm;
  if (req.landmarks) landmarks_mm = prepare_landmarks(*req.landmarks, out.scan.units);
  std::vector<fit::LandmarkTarget> targets = fit::match_landmarks(model, landmarks_mm);
  out.initial_landmarks = initialization_landmarks(targets, options);
  if (req.landmarks && targets.size() < kLandmarkNames.size()) {
    std::string missing;
    for (auto name : kLandmarkNames)
      if (!req.landmarks->find(name)) missing += std::string(missing.empty() ? "" : ", ") + std::string(name);
    out.warnings.push_back("landmarks missing (the fit uses those present): " + missing);
  }
  const std::vector<std::string> input_warnings = out.warnings;

  out.timings = target.timings;
  out.timings.front().seconds += phase.seconds();  // the landmarks' preparation
  Timer timer;  // from the index to fitted parameters
  fit::ScanTarget& scan = *target.target;
  if (const auto d = diagnose_landmark_frame(landmarks_mm, scan))
    throw InvalidInput(req.landmarks_name + ": the landmarks lie " + fmt(d->median_distance_mm) +
                       " mm from the scan (median); they look " + d->mistake + ": undone, they would lie " +
                       fmt(d->corrected_median_mm) +
                       " mm from it. Check the file's coordinate system and units");
  const bool refit = req.warm_start.has_value();
  out.fit = refit ? fit::refit_surface(model, scan, targets, options, *req.warm_start, on_iteration,
                                       req.warm_correspondences.get())
                  : fit::register_template(model, scan, targets, options, on_iteration);
  out.time_s = timer.seconds();
  const size_t fit_phases = out.fit.summary.timings.size();
  for (const auto& p : out.fit.summary.timings) out.timings.push_back(p);
  phase.reset();

  std::vector<std::string> far_landmarks;
  for (const auto& t : out.fit.landmarks) {
    const double d = std::sqrt(scan.closest(t.position).sq_dist);
    if (d > options.landmark_warning_mm)
      far_landmarks.push_back("landmark '" + t.name + "' is " + fmt(d) + " mm away from the scan surface");
  }
  // The warnings in their order: the input's, the fit's, the landmarks', the drawings', the plausibility's.
  auto collect_warnings = [&] {
    out.warnings = input_warnings;
    for (const auto& w : out.fit.summary.warnings) out.warnings.push_back(w);
    for (const auto& w : far_landmarks) out.warnings.push_back(w);
    for (const auto& c : out.drawings_on_scan)
      if (c.supported_fraction < 0.5)
        out.warnings.push_back("drawing '" + c.name + "': only " + fmt(100 * c.supported_fraction) + " % of it is on the scan");
    for (const auto& p : out.plausibility.problems) out.warnings.push_back("implausible fit: " + p);
  };
  out.fitted_mm.V = out.fit.vertices;
  out.fitted_mm.F = model.rest.F;
  out.model_landmarks_mm = evaluate_landmarks(model, out.fit.vertices, out.fit.params);
  out.landmarks = metrics::landmark_errors(model, out.fit.vertices, out.fit.params, out.fit.landmarks);
  transfer::TransferOptions transfer_options;
  transfer_options.reject_scan_border = !out.scan.was_point_cloud;
  metrics::CoverageOptions coverage_options;  // the surface error counts what the scan covers
  coverage_options.skip_border = !out.scan.was_point_cloud;
  TriangleMesh model_only;
  model_only.V = out.fit.model_vertices;
  model_only.F = model.rest.F;
  const bool with_detail = out.fit.detail_offsets.size() > 0;
  // The drawings' transfer, the breasts' measurements, the surface coverages (and a re-fit's
  // landmark checks) need only the fitted vertices: they run as independent tasks on the fit's
  // threads, the longest first (each writes only its own result, so the outputs do not depend on
  // the threads). `transfer`, `landmark_checks` and `measurements:breast_volumes` are those tasks'
  // own times, `measurements` the rest of the blocks' wall time.
  double transfer_s = 0;
  double breasts_s = 0;
  metrics::SurfaceCoverage model_only_coverage;
  std::vector<Index> faces;  // each fitted vertex's closest scan face: the model-only pass's warm starts
  const auto threads = static_cast<unsigned>(fit::resolve_threads(options.threads));
  auto measure_breasts = [&](unsigned breast_threads) {
    Timer own;
    out.breasts = transfer::measure_breasts(model, out.fit.vertices, {}, target.volumes.get(), breast_threads);
    breasts_s = own.seconds();
  };
  auto transfer_drawings = [&] {
    Timer own;
    out.drawings_on_scan = transfer::transfer_drawings(model, out.fit.vertices, scan, transfer_options);
    transfer_s = own.seconds();
  };
  auto cover_model_only = [&] {
    if (with_detail) model_only_coverage = metrics::surface_coverage(model_only, scan, coverage_options, &faces);
  };
  if (!refit) {
    run_in_order(3, threads, [&](std::size_t task) {
      switch (task) {
        case 0: measure_breasts(std::min(threads, 2u)); break;  // the longest: its two breasts on two threads
        case 1:
          out.coverage = metrics::surface_coverage(out.fitted_mm, scan, coverage_options, &faces);
          cover_model_only();
          break;
        default: transfer_drawings(); break;
      }
    });
  } else {
    // What the user needs at once: the fitted model and the drawings; then the rest. The landmark
    // checks (the longest task) need only the fitted parameters: with two threads they start on
    // the second one at once, beside the drawings' transfer; the two breasts and the coverage
    // passes are taken in order by whichever thread is free (each task writes only its own result).
    fit::FitOptions one_thread = options;  // each task on its own thread
    one_thread.threads = 1;
    transfer::BreastSideMeasurement sides[2];
    double side_s[2] = {0, 0};
    // The tasks write into their own objects, not into `out`, which the first result reads meanwhile.
    fit::FitResult checked = out.fit;
    metrics::SurfaceCoverage coverage;
    auto rest = [&](std::size_t task) {
      if (task < 2) {
        Timer own;
        sides[task] = transfer::measure_breast_side(model, out.fit.vertices, task == 0 ? 'R' : 'L', {},
                                                    target.volumes.get());
        side_s[task] = own.seconds();
      } else {
        coverage = metrics::surface_coverage(out.fitted_mm, scan, coverage_options, &faces);
        cover_model_only();
      }
    };
    // Task 0 the first result, task 1 the checks (side by side with two threads; in that order with
    // one), then the breasts and the coverage passes: at most two threads, as the checks expect.
    run_in_order(5, std::min(threads, 2u), [&](std::size_t task) {
      if (task == 1) {
        fit::check_refit(model, scan, one_thread, checked);
      } else if (task > 1) {
        rest(task - 2);
      } else {
        transfer_drawings();
        if (on_surface) {
          out.drawings_mm = transfer::to_markups(out.drawings_on_scan);
          out.complete = false;
          collect_warnings();
          PreparedScan kept = std::move(out.scan);  // not copied for the first result
          out.scan = PreparedScan{};
          on_surface(out);
          out.scan = std::move(kept);
          out.complete = true;
        }
      }
    });
    out.fit = std::move(checked);
    out.coverage = std::move(coverage);
    out.breasts = transfer::join_breast_sides(model, out.fit.vertices, std::move(sides[0]), std::move(sides[1]));
    breasts_s = side_s[0] + side_s[1];
    for (size_t k = fit_phases; k < out.fit.summary.timings.size(); ++k) out.timings.push_back(out.fit.summary.timings[k]);
  }
  out.drawings_mm = transfer::to_markups(out.drawings_on_scan);
  out.surface = out.coverage.stats();
  out.surface_model_only = with_detail ? model_only_coverage.stats() : out.surface;
  if (out.usable())
    out.plausibility = metrics::judge_plausibility(model, out.fit.params, out.coverage.fraction(), out.surface);
  collect_warnings();
  double checks_s = 0;
  for (size_t k = fit_phases; k < out.fit.summary.timings.size(); ++k) checks_s += out.fit.summary.timings[k].seconds;
  out.timings.push_back({"transfer", transfer_s});
  out.timings.push_back({"measurements", std::max(0.0, phase.seconds() - transfer_s - checks_s)});
  out.timings.push_back({"measurements:breast_volumes", breasts_s});  // a task of the blocks above
  return out;
}

}  // namespace breastfit::pipeline
