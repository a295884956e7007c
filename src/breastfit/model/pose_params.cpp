#include "breastfit/model/pose_params.h"

#include "breastfit/model/rigged_model.h"

namespace breastfit::model {

Similarity Similarity::inverse() const {
  // x = s R y + t  ⇔  y = (1/s) Rᵀ x − (1/s) Rᵀ t
  Similarity inv;
  inv.rotation = rotation.conjugate();
  inv.scale = 1.0 / scale;
  inv.translation = -inv.scale * (inv.rotation * translation);
  return inv;
}

Similarity Similarity::compose(const Similarity& other) const {
  // s1 R1 (s2 R2 x + t2) + t1
  Similarity c;
  c.rotation = (rotation * other.rotation).normalized();
  c.scale = scale * other.scale;
  c.translation = scale * (rotation * other.translation) + translation;
  return c;
}

PoseParams PoseParams::identity(const RiggedModel& model) {
  PoseParams p;
  p.bones.assign(model.bones.size(), BonePose{});
  p.alpha = Eigen::VectorXd::Zero(model.num_blendshapes());
  return p;
}

}  // namespace breastfit::model
