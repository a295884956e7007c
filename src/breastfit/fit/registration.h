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
#include <string>
#include <vector>

#include "breastfit/fit/fit_options.h"
#include "breastfit/fit/fit_summary.h"
#include "breastfit/fit/landmark_target.h"
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
};


/// Pairs input landmarks (name, position in mm) with the model's landmarks of the same name.
/// \throws InvalidInput for a name the model does not have, a duplicate or a non-finite position.
std::vector<LandmarkTarget> match_landmarks(const model::RiggedModel& model,
                                            const std::vector<std::pair<std::string, Vec3>>& landmarks_mm);

/// Registers `model` to `scan`. Landmarks may be empty (landmark-free initialisation).
/// Orients the scan's normals (ScanTarget::set_normal_sign) to agree with the template's.
/// How the solver ended is summary.termination; whether the result is usable is summary.verdict
/// (an unusable fit is reported there, not thrown). `on_iteration` may abort the run.
/// \throws InvalidInput for invalid options.
FitResult register_template(const model::RiggedModel& model, ScanTarget& scan,
                            std::vector<LandmarkTarget> landmarks, const FitOptions& options,
                            const IterationCallback& on_iteration = {});

/// A warm-started re-fit (e.g. after the user moved one landmark): starts from a previous fit's
/// parameters `start` and runs only the last stage (options.refine): no initialisation, no coarse
/// stages, no L/R swap detection. The final state, verdict, surface detail and landmark checks
/// are those of register_template; summary.initialization is "warm start".
/// \throws InvalidInput for invalid options or parameters of another template.
FitResult refit_template(const model::RiggedModel& model, ScanTarget& scan, std::vector<LandmarkTarget> landmarks,
                         const FitOptions& options, const model::PoseParams& start,
                         const IterationCallback& on_iteration = {});

}  // namespace breastfit::fit
