#pragma once
/// \file Standard views of a torso, defined in the body frame (LPS: x = patient's left,
/// y = posterior, z = superior) and carried into the world by a body→world transform.
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "breastfit/core/types.h"

namespace breastfit::render {

enum class View {
  Front,    ///< from the anterior side (camera at −y, looking +y), superior up; the patient's
            ///< right appears on the viewer's LEFT
  Side,     ///< from the patient's right side (camera at −x, looking +x), superior up; anterior
            ///< appears on the viewer's right
  Oblique,  ///< 45° between Front and Side (camera front-right), superior up
  SideLeft,     ///< from the patient's left side (camera at +x, looking −x); anterior on the left
  ObliqueLeft,  ///< 45° between Front and SideLeft (camera front-left), superior up
  Back,     ///< from the posterior side (camera at +y), superior up
  Top,      ///< from above (camera at +z, looking −z), anterior up in the image
};

/// Viewing direction (camera → scene) and image-up direction, both unit vectors in world
/// coordinates.
struct ViewDirections {
  Vec3 forward;
  Vec3 up;
};

/// Directions of a view for a torso whose body frame maps to the world by `body_to_world`
/// (4×4 affine; only its linear part is used, orthonormalised, so a uniform scale is harmless).
/// \throws InvalidInput if the linear part is singular or not finite.
ViewDirections view_directions(View view, const Eigen::Matrix4d& body_to_world = Eigen::Matrix4d::Identity());

/// "front", "side", "oblique", "side-left", "oblique-left", "back", "top" (side and oblique are
/// the patient's right).
std::string_view view_name(View view);
/// Inverse of view_name (also accepts "side-right", "oblique-right").
/// \throws InvalidInput for an unknown name, listing the known ones.
View view_from_name(std::string_view name);
/// Every view: Front, Back, Top and the sides and obliques.
std::vector<View> all_views();
/// The views written by `--view all`: Front, Side, SideLeft, Oblique, ObliqueLeft.
std::vector<View> default_views();

}  // namespace breastfit::render
