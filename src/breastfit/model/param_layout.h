#pragma once
/// \file Flat parameter vector layout for the solver: which entry is which parameter,
/// parameter names (params.json), and the update rule x ← x ⊞ δ.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "breastfit/model/pose_params.h"

namespace breastfit::model {

/// Layout of the increment vector δ (size num_params()):
///  [0,3)   global rotation increment ω_g (R_g ← exp([ω_g]×) R_g)
///  [3,6)   global translation (mm)
///  6       global log-scale increment (s_g ← s_g · exp(δ))
///  then per bone j (9 entries at bone_offset(j)): ω_j (3), t_j (3, mm), s_j (3, additive)
///  then per blendshape k: α_k (additive) at blendshape_offset(k)
enum class ParamKind { GlobalRotation, GlobalTranslation, GlobalScale, BoneRotation, BoneTranslation,
                       BoneScale, Blendshape };

class ParamLayout {
 public:
  explicit ParamLayout(const RiggedModel& model);

  int num_params() const { return num_params_; }
  int num_bones() const { return num_bones_; }
  int num_blendshapes() const { return num_blendshapes_; }
  static constexpr int global_offset() { return 0; }
  static constexpr int kGlobalSize = 7;
  static constexpr int kBoneSize = 9;
  int bone_offset(int bone) const { return kGlobalSize + kBoneSize * bone; }
  int blendshape_offset(int k) const { return kGlobalSize + kBoneSize * num_bones_ + k; }

  ParamKind kind(int index) const;
  /// Stable human-readable name, e.g. "global.rotation.x", "bone.thorax.scale.y", "shape.breast_volume_R".
  std::string name(int index) const;

  /// x ← x ⊞ δ: rotations by left-multiplied exponential increments, the global scale
  /// multiplicatively, the rest additively; then bone scales and blendshape weights are
  /// clamped to their bounds. `delta` has size num_params().
  void apply_increment(const RiggedModel& model, const Eigen::VectorXd& delta, PoseParams& params) const;

  /// Clamps bone scales and blendshape weights of `params` to the model's bounds.
  void clamp_to_bounds(const RiggedModel& model, PoseParams& params) const;

 private:
  int num_bones_ = 0;
  int num_blendshapes_ = 0;
  int num_params_ = 0;
  std::vector<std::string> bone_names_;
  std::vector<std::string> shape_names_;
};

}  // namespace breastfit::model
