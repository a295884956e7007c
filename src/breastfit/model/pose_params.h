#pragma once
/// \file The parameters θ of a posed template (docs/MODEL.md).
#include <vector>

#include <Eigen/Core>

#include "breastfit/core/types.h"

namespace breastfit::model {

struct RiggedModel;

/// x ↦ scale · rotation · x + translation, applied after skinning. Never regularised.
struct Similarity {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();
  double scale = 1.0;

  Vec3 apply(const Vec3& x) const { return scale * (rotation * x) + translation; }
  Similarity inverse() const;
  /// this ∘ other (apply `other` first).
  Similarity compose(const Similarity& other) const;
};

/// Per bone: rotation about the pivot, translation, scale along the rest axes.
struct BonePose {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();
  Vec3 scale = Vec3::Ones();
};

struct PoseParams {
  Similarity global;
  std::vector<BonePose> bones;   ///< one per bone
  Eigen::VectorXd alpha;         ///< one weight per blendshape

  /// The rest pose of `model`: identity similarity and bones, zero blendshape weights.
  static PoseParams identity(const RiggedModel& model);
};

}  // namespace breastfit::model
