#pragma once
/// \file Landmarks that are not material points. The lowest breast point is defined as the lowest
/// point of the breast (its footprint region, border included) along the body's vertical axis *in
/// the current pose*: on the hanging lower pole when standing, at the fold when supine. A fixed
/// template point cannot follow that, so its model position is re-chosen on the posed model at
/// every iteration.
#include <optional>
#include <string>

#include "breastfit/core/types.h"
#include "breastfit/mesh/surface_point.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

namespace breastfit::fit {

/// The template region a sliding landmark is the lowest point of ("breast_R" for
/// "lowest_breast_R"), or nullopt for material landmarks.
std::optional<std::string> sliding_landmark_region(const std::string& landmark_name);

/// The body's vertical (superior) axis in the posed frame: the global rotation applied to the
/// thorax bone's rotation of the template's +z (the template's vertical when it has no "thorax").
Vec3 posed_vertical_axis(const model::RiggedModel& model, const model::PoseParams& params);

/// The vertex of `region` lowest along `vertical` on the posed vertices V, as a surface point;
/// nullopt when the model has no such region.
std::optional<SurfacePoint> lowest_region_point(const model::RiggedModel& model, const Points& V,
                                                const Vec3& vertical, const std::string& region);

/// Position of a model landmark on posed vertices V: the sliding definition for the lowest breast
/// points (when the model has the regions), the stored surface point otherwise.
Vec3 model_landmark_position(const model::RiggedModel& model, int landmark, const Points& V,
                             const model::PoseParams& params);

}  // namespace breastfit::fit
