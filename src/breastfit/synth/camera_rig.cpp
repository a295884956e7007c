#include "breastfit/synth/camera_rig.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "breastfit/core/errors.h"
#include "breastfit/spatial/ray_caster.h"

namespace breastfit::synth {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Camera look_at(const Vec3& position, const Vec3& target) {
  Camera c;
  c.position = position;
  c.forward = (target - position).normalized();
  Vec3 right = c.forward.cross(Vec3::UnitZ());
  if (right.norm() < 1e-9) right = Vec3::UnitX();
  c.right = right.normalized();
  c.up = c.right.cross(c.forward).normalized();
  return c;
}

}  // namespace

std::vector<Camera> camera_rig(const ScannerOptions& o, PoseType pose, const Vec3& centre) {
  const double arc = (pose == PoseType::Standing ? o.arc_deg_standing : o.arc_deg_supine) * kDeg;
  std::vector<Camera> cams;
  for (double elevation_deg : o.elevations_deg) {
    const double e = elevation_deg * kDeg;
    for (int a = 0; a < o.n_azimuth; ++a) {
      // From patient right (-x) over the front (-y) to patient left (+x).
      const double t = o.n_azimuth == 1 ? 0.5 : static_cast<double>(a) / (o.n_azimuth - 1);
      const double phi = -0.5 * arc + t * arc;
      const Vec3 dir = std::cos(e) * Vec3(std::sin(phi), -std::cos(phi), 0.0) + std::sin(e) * Vec3::UnitZ();
      cams.push_back(look_at(centre + o.distance_mm * dir, centre));
    }
  }
  return cams;
}

std::vector<int> count_views(const TriangleMesh& surface, const Points& normals, const std::vector<Camera>& cameras,
                             const ScannerOptions& o, int stop_at) {
  if (stop_at < 1) throw InvalidInput("count_views: stop_at must be >= 1");
  if (normals.rows() != surface.V.rows()) throw InvalidInput("count_views: one normal per vertex is needed");
  const Index nv = surface.num_vertices();
  std::vector<int> views(static_cast<size_t>(nv), 0);
  if (cameras.empty() || nv == 0) return views;
  const spatial::RayCaster caster(surface);
  const double tan_h = std::tan(0.5 * o.fov_horizontal_deg * kDeg);
  const double tan_v = std::tan(0.5 * o.fov_vertical_deg * kDeg);
  const double cos_max = std::cos(o.max_incidence_deg * kDeg);
  std::vector<std::pair<double, int>> order;
  order.reserve(cameras.size());
  for (Index v = 0; v < nv; ++v) {
    const Vec3 p = surface.V.row(v).transpose();
    const Vec3 n = normals.row(v).transpose();
    if (n.squaredNorm() < 0.5) continue;
    // Candidate cameras: in the field of view and facing, most frontal first (early exit).
    order.clear();
    for (size_t c = 0; c < cameras.size(); ++c) {
      const Camera& cam = cameras[c];
      const Vec3 d = p - cam.position;
      const double z = d.dot(cam.forward);
      if (z <= 0) continue;
      if (std::abs(d.dot(cam.right)) > tan_h * z || std::abs(d.dot(cam.up)) > tan_v * z) continue;
      const double cos_inc = -n.dot(d) / d.norm();
      if (cos_inc < cos_max) continue;
      order.emplace_back(-cos_inc, static_cast<int>(c));
    }
    std::sort(order.begin(), order.end());
    int count = 0;
    for (const auto& [key, c] : order) {
      const Vec3 origin = p + 0.3 * n;  // off the surface it starts on
      if (!caster.occluded(origin, cameras[static_cast<size_t>(c)].position, 1e-3)) {
        if (++count >= stop_at) break;
      }
    }
    views[static_cast<size_t>(v)] = count;
  }
  return views;
}

}  // namespace breastfit::synth
