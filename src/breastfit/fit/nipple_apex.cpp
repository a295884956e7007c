#include "breastfit/fit/nipple_apex.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace breastfit::fit {

std::optional<Vec3> nipple_apex_on_scan(const Points& scan_vertices, const Points& model_vertices,
                                        const Points& model_normals, const Vec3& model_nipple, const Vec3& up,
                                        const NippleApexOptions& options) {
  Vec3 forward = Vec3::Zero();
  for (Index i = 0; i < model_vertices.rows(); ++i)
    if ((model_vertices.row(i).transpose() - model_nipple).norm() < options.normal_radius_mm)
      forward += model_normals.row(i).transpose();
  forward -= forward.dot(up) * up;
  if (!(forward.norm() > 0)) return std::nullopt;
  forward.normalize();
  double best = -std::numeric_limits<double>::infinity();
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const Vec3 d = scan_vertices.row(i).transpose() - model_nipple;
    if (d.norm() < options.search_radius_mm) best = std::max(best, d.dot(forward));
  }
  if (!std::isfinite(best)) return std::nullopt;
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (Index i = 0; i < scan_vertices.rows(); ++i) {
    const Vec3 d = scan_vertices.row(i).transpose() - model_nipple;
    if (d.norm() < options.search_radius_mm && d.dot(forward) >= best - options.cap_mm) {
      sum += scan_vertices.row(i).transpose();
      ++n;
    }
  }
  return Vec3(sum / n);
}

}  // namespace breastfit::fit
