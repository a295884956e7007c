#pragma once
/// \file Regularisers of the pose and shape (paper eqs. 5–7) and the joint continuity penalty.
///   E_S  = Σ_j ‖s_j − 1‖²
///   E_BS = Σ_k α_k²                       (the paper writes ‖α‖; squared is smooth at 0)
///   E_J  = Σ_j ‖log(R_parent(j)ᵀ R_j)‖² + ‖t_root / τ‖²
///          rotations relative to the parent bone (the root relative to the global similarity);
///          child translations are tied to their parent by the continuity term instead
///   E_C  = Σ_{j≠root} ‖P_parent(j)(c_j) − P_j(c_j)‖²   (the joint point moved by both bones)
#include "breastfit/fit/normal_equations.h"
#include "breastfit/model/pose_evaluator.h"

namespace breastfit::fit {

struct PriorScales {
  double scale = 0.0;       ///< 1/λS
  double blendshape = 0.0;  ///< 1/λBS
  double joint = 0.0;       ///< 1/λJ
  double continuity = 0.0;  ///< 1/λC
  double joint_translation_scale_mm = 10.0;  ///< τ
};

struct PriorCosts {
  double scale = 0, blendshape = 0, joint = 0, continuity = 0;
  double total() const { return scale + blendshape + joint + continuity; }
};

/// Costs of the priors at the evaluator's current parameters; with `eq`, also their normal equations.
PriorCosts add_priors(const model::PoseEvaluator& ev, const PriorScales& scales, NormalEquations* eq);

}  // namespace breastfit::fit
