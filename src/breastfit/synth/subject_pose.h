#pragma once
/// \file The random subject of a synthetic case: blendshape weights, bone scales and rotations,
/// arm abduction/flexion (standing or supine) and, for supine subjects, the breast displacement
/// blendshapes. Body frame (LPS mm); the global similarity keeps rotation identity and zero
/// translation (the scanner transform is applied separately), only its uniform scale varies.
#include <string>
#include <vector>

#include "breastfit/core/rng.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"
#include "breastfit/synth/synth_options.h"

namespace breastfit::synth {

/// How one arm was posed (only for models with bones "upper_arm_R" / "upper_arm_L").
struct ArmPose {
  std::string side;                ///< "R" or "L"
  double rest_abduction_deg = 0;   ///< abduction of the template's rest pose (first bone axis)
  double abduction_deg = 0;        ///< drawn abduction from the vertical
  double flexion_deg = 0;          ///< drawn flexion (forward > 0)
};

struct SubjectPose {
  model::PoseParams params;        ///< the true parameters (body frame)
  std::vector<ArmPose> arms;       ///< the posed arms (empty when the model has none)
  std::vector<std::string> supine_shapes;  ///< blendshapes set by the supine displacement rule
};

/// Draws the subject. Deterministic in `rng`'s state.
/// \pre model.validate() passes; options.validate() passes
SubjectPose sample_subject_pose(const model::RiggedModel& model, const SynthOptions& options, Rng& rng);

}  // namespace breastfit::synth
