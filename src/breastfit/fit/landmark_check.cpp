#include "breastfit/fit/landmark_check.h"

#include <limits>

namespace breastfit::fit {

double landmark_check_tolerance_mm(const std::string& name, double landmark_check_mm) {
  return landmark_weight(name) < 1.0 ? 2.0 * landmark_check_mm : landmark_check_mm;
}

std::optional<Vec3> breast_tip_on_scan(const Points& scan_vertices, const Points& model_vertices,
                                       const Points& model_normals, const Vec3& model_nipple,
                                       double search_radius_mm) {
  Vec3 outward = Vec3::Zero();
  for (Index i = 0; i < model_vertices.rows(); ++i)
    if ((model_vertices.row(i).transpose() - model_nipple).norm() < 40.0) outward += model_normals.row(i).transpose();
  if (outward.norm() <= 0) return std::nullopt;
  outward.normalize();
  std::optional<Vec3> tip;
  double best = -std::numeric_limits<double>::infinity();
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const Vec3 d = scan_vertices.row(i).transpose() - model_nipple;
    if (d.norm() >= search_radius_mm) continue;
    const double h = d.dot(outward);
    if (h > best) {
      best = h;
      tip = scan_vertices.row(i).transpose();
    }
  }
  return tip;
}

double robust_landmark_factor(double distance_mm, double tolerance_mm) {
  if (!(distance_mm > tolerance_mm)) return 1.0;
  const double q = tolerance_mm / distance_mm;
  return q * q;
}

}  // namespace breastfit::fit
