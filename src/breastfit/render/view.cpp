#include "breastfit/render/view.h"

#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "breastfit/core/errors.h"

namespace breastfit::render {

ViewDirections view_directions(View view, const Eigen::Matrix4d& body_to_world) {
  const Eigen::Matrix3d A = body_to_world.topLeftCorner<3, 3>();
  if (!A.allFinite()) throw InvalidInput("view_directions: body_to_world is not finite");
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sv = svd.singularValues();
  if (!(sv[2] > 1e-12 * std::max(1.0, sv[0])))
    throw InvalidInput("view_directions: body_to_world's linear part is singular");
  // Nearest rotation (polar decomposition); a reflection is kept as given.
  const Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();

  Vec3 forward(0, 1, 0), up(0, 0, 1);
  switch (view) {
    case View::Front:
      forward = Vec3(0, 1, 0);
      break;
    case View::Side:
      forward = Vec3(1, 0, 0);
      break;
    case View::Oblique:
      forward = Vec3(1, 1, 0).normalized();
      break;
    case View::SideLeft:
      forward = Vec3(-1, 0, 0);
      break;
    case View::ObliqueLeft:
      forward = Vec3(-1, 1, 0).normalized();
      break;
    case View::Back:
      forward = Vec3(0, -1, 0);
      break;
    case View::Top:
      forward = Vec3(0, 0, -1);
      up = Vec3(0, -1, 0);
      break;
  }
  return {(R * forward).normalized(), (R * up).normalized()};
}

std::string_view view_name(View view) {
  switch (view) {
    case View::Front:
      return "front";
    case View::Side:
      return "side";
    case View::Oblique:
      return "oblique";
    case View::SideLeft:
      return "side-left";
    case View::ObliqueLeft:
      return "oblique-left";
    case View::Back:
      return "back";
    case View::Top:
      return "top";
  }
  return "front";
}

std::vector<View> all_views() {
  return {View::Front, View::Side, View::Oblique, View::SideLeft, View::ObliqueLeft, View::Back, View::Top};
}

View view_from_name(std::string_view name) {
  if (name == "side-right") return View::Side;
  if (name == "oblique-right") return View::Oblique;
  std::string known;
  for (View v : all_views()) {
    if (view_name(v) == name) return v;
    known += (known.empty() ? "" : ", ") + std::string(view_name(v));
  }
  throw InvalidInput("unknown view '" + std::string(name) + "' (known: " + known + ")");
}

std::vector<View> default_views() { return {View::Front, View::Side, View::SideLeft, View::Oblique, View::ObliqueLeft}; }

}  // namespace breastfit::render
