#pragma once
/// \file Where the scan's anatomy and the other landmarks put each given landmark: a linearised
/// leave-one-out of the fit.
///
/// After the fit, the template has followed every landmark, a wrong one included (the breasts'
/// skin slides, the bones and shapes have the freedom), so "given vs fitted" stays small. Leaving
/// landmark l out changes the energy's gradient by its own part g_l and its Gauss–Newton matrix
/// by H_l; one Newton step of the energy without it,
///   δ_l = −(H − H_l)⁻¹ (g − g_l),
/// from the fitted parameters (at the final correspondences) says where the data, the priors and
/// the other landmarks take the model, and the model's landmark l there is its *prediction*. For
/// a linear least-squares problem this is exactly the leave-one-out fit (the residual divided by
/// one minus the landmark's leverage); here it costs one assembly of H and one small solve per
/// landmark (~1 ms each with the default template), instead of a re-fit per landmark.
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/fit/problem.h"
#include "breastfit/model/pose_params.h"

namespace breastfit::fit {

/// The parameters of one Newton step from `params` of `problem`'s energy with the landmarks
/// `left_out` (indices into problem.landmarks()) removed, over the parameters `active` (full
/// indices). `problem`'s correspondences and terms are those of `params` (update them first).
/// The evaluator is left at `params`.
model::PoseParams leave_out_landmarks(Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                                      const std::vector<size_t>& left_out);

/// For each of problem.landmarks() (in that order), the model's landmark position after the step of
/// leave_out_landmarks with that landmark alone left out (one assembly and one factorisation of H
/// for all: each landmark's own rows are a low-rank update). With `steps`, also the parameters after
/// each step (predict_left_out_relinearized's first step).
std::vector<Vec3> predict_left_out_landmarks(Problem& problem, const model::PoseParams& params,
                                             const std::vector<int>& active,
                                             std::vector<model::PoseParams>* steps = nullptr);

/// The correspondences a re-linearised leave-one-out recomputes after each step.
struct Relinearization {
  double max_distance_mm = 15.0;  ///< correspondence threshold (the fit's final one)
  bool with_reverse = false;      ///< the reverse term is used
  bool robust_landmarks = false;  ///< the landmark terms' robust factors (as in the final stage)
};

/// The prediction of landmark `i` (of problem.landmarks()) from `steps` Newton steps of the
/// energy without it, each from the previous one with the correspondences recomputed: the path
/// back over the curved skin that one linear step (predict_left_out_landmarks) cuts short — a
/// landmark walked 20–40 mm along the skin is predicted farther from the click. The first step is
/// the linear one (`linear_step` when given: predict_left_out_landmarks' parameters for landmark
/// `i`, at the same correspondences, not computed again); a later step that raises the energy
/// without the landmark (at its own correspondences) ends the walk. The problem is left
/// at `params` with its correspondences and terms recomputed there.
Vec3 predict_left_out_relinearized(Problem& problem, const model::PoseParams& params, const std::vector<int>& active,
                                   size_t i, int steps, const Relinearization& relinearization,
                                   const model::PoseParams* linear_step = nullptr);

}  // namespace breastfit::fit
