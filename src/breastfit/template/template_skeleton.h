#pragma once
/// \file The template's 9 scalable bones (pivots and rest axes from the body parameters) and the
/// per-vertex seeds their heat-diffusion skin weights start from.
#include <vector>

#include <Eigen/Core>

#include "breastfit/model/rigged_model.h"
#include "breastfit/template/body_field.h"
#include "breastfit/template/template_mesh.h"

namespace breastfit::templ {

/// Bone indices in the order of template_bones() (parents first).
enum TemplateBone : int {
  kAbdomen = 0, kThorax, kNeck, kClavicleR, kClavicleL, kUpperArmR, kUpperArmL, kBreastR, kBreastL,
  kNumTemplateBones
};

/// abdomen (root, pivot at the abdomen centre), thorax (pivot ~T12), neck (neck base),
/// clavicle_R/L (sterno-clavicular joints, first axis along the clavicle), upper_arm_R/L
/// (gleno-humeral joint centres, first axis along the humerus), breast_R/L (centre of the breast
/// base, first axis along the breast axis).
std::vector<model::Bone> template_bones(const BodyField& field);

/// The acromion (bony top of the shoulder) of a side, mm; also the lateral end of the clavicle.
Vec3 acromion_point(const BodyField& field, int side);

/// Height of each vertex above the chest wall (value_without_breasts, >= 0), #V.
Eigen::VectorXd breast_height(const TriangleMesh& mesh, const BodyField& field);

/// #V by 9 seeds: a partition of the surface by anatomy (arm beyond the axilla, shoulder cap,
/// neck above the notch, abdomen below ~T12, thorax) blended with the breast mounds.
Eigen::MatrixXd skin_weight_seeds(const TemplateMesh& tm, const BodyField& field,
                                  const Eigen::VectorXd& breast_height);

}  // namespace breastfit::templ
