#pragma once
/// \file Pose parameters ↔ JSON by parameter name (params.json), any subset.
///
/// Format: an object whose keys are ParamLayout::name()s with numbers as values:
///   "global.rotation.x|y|z"          rotation vector of R_g (axis · angle, radians)
///   "global.translation.x|y|z"       t_g, mm
///   "global.scale"                   s_g (the factor itself, > 0)
///   "bone.<bone>.rotation.x|y|z"     rotation vector of R_j (radians)
///   "bone.<bone>.translation.x|y|z"  t_j, mm
///   "bone.<bone>.scale.x|y|z"        s_j along the bone's rest axes
///   "shape.<blendshape>"             α_k
/// Either that object is the whole document, or it is the member "params" of the document
/// (written that way, so other top-level members — format, version, notes — are metadata).
/// Missing names keep the value of the base parameters (the rest pose by default); a rotation
/// given partly keeps the other components of the base rotation vector.
///
/// Example:
/// \code
///   {"params": {"global.scale": 1.1, "bone.chest.rotation.x": 0.2, "shape.breast_volume_R": 0.5}}
/// \endcode
#include <filesystem>

#include <nlohmann/json.hpp>

#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::model {

/// Every parameter of `params` by name, wrapped as
/// {"format": "breastfit.params", "version": 1, "params": {name: value, ...}}.
/// \throws InvalidInput if `params` does not match the model's sizes
nlohmann::json params_to_json(const RiggedModel& model, const PoseParams& params);

/// Parameters read by name from `doc` (the flat object or the {"params": {...}} wrapper),
/// starting from `base` (the rest pose when omitted).
/// \throws InvalidInput for an unknown name (the message lists examples of valid names), a
///         non-numeric or non-finite value, a scale ≤ 0, or a bone scale / blendshape weight
///         outside the model's bounds
PoseParams params_from_json(const RiggedModel& model, const nlohmann::json& doc);
PoseParams params_from_json(const RiggedModel& model, const nlohmann::json& doc, const PoseParams& base);

/// Reads a params.json file (see params_from_json).
/// \throws IoError if the file is missing or not JSON; InvalidInput as params_from_json
PoseParams read_params_json(const std::filesystem::path& path, const RiggedModel& model);

/// Writes params_to_json(model, params) to `path` (pretty-printed).
/// \throws IoError if the file cannot be written
void write_params_json(const std::filesystem::path& path, const RiggedModel& model, const PoseParams& params);

}  // namespace breastfit::model
