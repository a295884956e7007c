#include "breastfit/model/param_layout.h"

#include <algorithm>
#include <cmath>

#include "breastfit/core/errors.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::model {
namespace {

constexpr const char* kAxis[3] = {"x", "y", "z"};

/// exp([ω]×) as a unit quaternion.
Quat rotation_exp(const Vec3& omega) {
  const double angle = omega.norm();
  if (angle < 1e-12) return Quat(1.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z()).normalized();
  return Quat(Eigen::AngleAxisd(angle, omega / angle));
}

void check_sizes(const ParamLayout& layout, const PoseParams& params) {
  if (static_cast<int>(params.bones.size()) != layout.num_bones())
    throw InvalidInput("pose parameters have " + std::to_string(params.bones.size()) + " bones, the model has " +
                       std::to_string(layout.num_bones()));
  if (params.alpha.size() != layout.num_blendshapes())
    throw InvalidInput("pose parameters have " + std::to_string(params.alpha.size()) +
                       " blendshape weights, the model has " + std::to_string(layout.num_blendshapes()));
}

}  // namespace

ParamLayout::ParamLayout(const RiggedModel& model)
    : num_bones_(model.num_bones()), num_blendshapes_(model.num_blendshapes()) {
  num_params_ = kGlobalSize + kBoneSize * num_bones_ + num_blendshapes_;
  bone_names_.reserve(model.bones.size());
  for (const auto& b : model.bones) bone_names_.push_back(b.name);
  shape_names_.reserve(model.blendshapes.size());
  for (const auto& s : model.blendshapes) shape_names_.push_back(s.name);
}

ParamKind ParamLayout::kind(int index) const {
  if (index < 0 || index >= num_params_)
    throw InvalidInput("parameter index " + std::to_string(index) + " out of range [0, " +
                       std::to_string(num_params_) + ")");
  if (index < 3) return ParamKind::GlobalRotation;
  if (index < 6) return ParamKind::GlobalTranslation;
  if (index < kGlobalSize) return ParamKind::GlobalScale;
  if (index < blendshape_offset(0)) {
    const int local = (index - kGlobalSize) % kBoneSize;
    if (local < 3) return ParamKind::BoneRotation;
    if (local < 6) return ParamKind::BoneTranslation;
    return ParamKind::BoneScale;
  }
  return ParamKind::Blendshape;
}

std::string ParamLayout::name(int index) const {
  switch (kind(index)) {
    case ParamKind::GlobalRotation: return std::string("global.rotation.") + kAxis[index];
    case ParamKind::GlobalTranslation: return std::string("global.translation.") + kAxis[index - 3];
    case ParamKind::GlobalScale: return "global.scale";
    case ParamKind::BoneRotation:
    case ParamKind::BoneTranslation:
    case ParamKind::BoneScale: {
      const int bone = (index - kGlobalSize) / kBoneSize;
      const int local = (index - kGlobalSize) % kBoneSize;
      static constexpr const char* kPart[3] = {"rotation", "translation", "scale"};
      return "bone." + bone_names_[bone] + "." + kPart[local / 3] + "." + kAxis[local % 3];
    }
    case ParamKind::Blendshape: return "shape." + shape_names_[index - blendshape_offset(0)];
  }
  return {};
}

void ParamLayout::apply_increment(const RiggedModel& model, const Eigen::VectorXd& delta,
                                  PoseParams& params) const {
  if (delta.size() != num_params_)
    throw InvalidInput("parameter increment has size " + std::to_string(delta.size()) + ", expected " +
                       std::to_string(num_params_));
  check_sizes(*this, params);
  params.global.rotation = (rotation_exp(delta.segment<3>(0)) * params.global.rotation).normalized();
  params.global.translation += delta.segment<3>(3);
  params.global.scale *= std::exp(delta[6]);
  for (int j = 0; j < num_bones_; ++j) {
    const int o = bone_offset(j);
    BonePose& b = params.bones[j];
    b.rotation = (rotation_exp(delta.segment<3>(o)) * b.rotation).normalized();
    b.translation += delta.segment<3>(o + 3);
    b.scale += delta.segment<3>(o + 6);
  }
  params.alpha += delta.segment(blendshape_offset(0), num_blendshapes_);
  clamp_to_bounds(model, params);
}

void ParamLayout::clamp_to_bounds(const RiggedModel& model, PoseParams& params) const {
  check_sizes(*this, params);
  if (model.num_bones() != num_bones_ || model.num_blendshapes() != num_blendshapes_)
    throw InvalidInput("parameter layout does not match the model");
  for (int j = 0; j < num_bones_; ++j) {
    const Bone& bone = model.bones[j];
    params.bones[j].scale = params.bones[j].scale.cwiseMax(bone.scale_lo).cwiseMin(bone.scale_hi);
  }
  for (int k = 0; k < num_blendshapes_; ++k) {
    const Blendshape& s = model.blendshapes[k];
    params.alpha[k] = std::clamp(params.alpha[k], s.lo, s.hi);
  }
}

}  // namespace breastfit::model
