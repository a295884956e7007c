#pragma once
/// \file The registration (paper §2.8, docs/REGISTRATION.md): coarse-to-fine Levenberg–Marquardt
/// over the template's parameters with closest-point correspondences recomputed every iteration.
///
/// Example:
/// \code
///   fit::ScanTarget scan(scan_mm);                       // builds the closest-point index
///   auto targets = fit::match_landmarks(model, input_landmarks_mm);
///   fit::FitResult r = fit::register_template(model, scan, targets, fit::FitOptions{});
///   if (!r.summary.usable()) { ... r.summary.message ... }
/// \endcode
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/fit_summary.h"
#include "breastfit/fit/landmark_target.h"
#include "breastfit/fit/problem.h"
#include "breastfit/fit/scan_target.h"
#include "breastfit/fit/surface_detail.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::fit {

struct FitResult {
  model::PoseParams params;               ///< fitted parameters θ*
  Points vertices;                        ///< posed template vertices (+ surface detail), mm, scan frame
  Points model_vertices;                  ///< the posed template alone (the paper's model), mm, scan frame
  Eigen::VectorXd detail_offsets;         ///< surface-detail offsets along model_vertices' normals (empty: none)
  std::vector<LandmarkTarget> landmarks;  ///< the input landmarks as used (after any L/R correction)
  FitSummary summary;
  /// The final state's correspondences (at `params`, the final threshold; null when the fit did not
  /// reach its final state): a re-fit from `params` finds its first ones there, and the re-fit's
  /// landmark checks theirs (the same pairs, not searched again).
  std::shared_ptr<const Problem::CorrespondenceState> final_correspondences;
};


/// Pairs input landmarks (name, position in mm) with the model's landmarks of the same name.
/// \throws InvalidInput for a name the model does not have, a duplicate or a non-finite position.
std::vector<LandmarkTarget> match_landmarks(const model::RiggedModel& model,
                                            const std::vector<std::pair<std::string, Vec3>>& landmarks_mm);

/// The landmarks register_template fits, of `targets`: none without options.use_landmarks, at most
/// options.max_landmarks (the first ones, in the paper's order).
std::vector<LandmarkTarget> select_landmarks(std::vector<LandmarkTarget> targets, const FitOptions& options);

/// Registers `model` to `scan`. Landmarks may be empty (landmark-free initialisation).
/// Orients the scan's normals (ScanTarget::set_normal_sign) to agree with the template's.
/// How the solver ended is summary.termination; whether the result is usable is summary.verdict
/// (an unusable fit is reported there, not thrown). `on_iteration` may abort the run.
/// summary.timings end with "landmark_checks" (the given landmarks' checks; a refine stage they
/// run again is its own "stage:refine").
/// \throws InvalidInput for invalid options.
FitResult register_template(const model::RiggedModel& model, ScanTarget& scan,
                            std::vector<LandmarkTarget> landmarks, const FitOptions& options,
                            const IterationCallback& on_iteration = {});

/// A warm-started re-fit (e.g. after the user moved one landmark): starts from a previous fit's
/// parameters `start` and runs only the last stage (options.refine): no initialisation, no coarse
/// stages, no L/R swap detection. The final state, verdict, surface detail and landmark checks
/// are those of register_template; summary.initialization is "warm start".
/// refit_surface then check_refit (pipeline::register_prepared runs the two apart, the checks beside
/// the breast measurements). summary.timings end with "landmark_checks".
/// \throws InvalidInput for invalid options or parameters of another template.
FitResult refit_template(const model::RiggedModel& model, ScanTarget& scan, std::vector<LandmarkTarget> landmarks,
                         const FitOptions& options, const model::PoseParams& start,
                         const IterationCallback& on_iteration = {});

/// refit_template's first part, what the user needs at once: the refine stage from `start`, the
/// final state, verdict and surface detail; no landmark checks (summary.landmark_checks empty,
/// their warnings missing: check_refit adds them). result.landmarks are the landmarks as used.
/// `start_correspondences`: the previous fit's FitResult::final_correspondences (a fit of the same
/// scan with the same options): the first iteration's pairs when found at `start` (the same
/// pairs as a search; null: searched). \throws InvalidInput as refit_template.
FitResult refit_surface(const model::RiggedModel& model, ScanTarget& scan, std::vector<LandmarkTarget> landmarks,
                        const FitOptions& options, const model::PoseParams& start,
                        const IterationCallback& on_iteration = {},
                        const Problem::CorrespondenceState* start_correspondences = nullptr);

/// refit_template's second part on refit_surface's `result` (same model, scan and options): the
/// landmark checks, reported only (summary.landmark_checks and their warnings; the re-fit does not
/// hold a landmark off), and the phase "landmark_checks".
void check_refit(const model::RiggedModel& model, ScanTarget& scan, const FitOptions& options, FitResult& result);

}  // namespace breastfit::fit
