#include "breastfit/fit/midline_notch_check.h"

#include <cmath>

#include "breastfit/fit/jugular_notch.h"

namespace breastfit::fit {

std::optional<MidPlane> landmark_midplane(const std::vector<LandmarkTarget>& landmarks, const std::string& skip) {
  Vec3 right_to_left = Vec3::Zero(), sum = Vec3::Zero();
  int points = 0;
  for (const char* pair : {"acromion_", "midaxillary_", "pectoral_insertion_", "nipple_", "lowest_breast_"}) {
    const std::string r = std::string(pair) + "R", l = std::string(pair) + "L";
    const LandmarkTarget* a = find_landmark(landmarks, r);
    const LandmarkTarget* b = find_landmark(landmarks, l);
    if (!a || !b || r == skip || l == skip) continue;
    right_to_left += (b->position - a->position).normalized();
    sum += 0.5 * (a->position + b->position);
    ++points;
  }
  if (points == 0 || right_to_left.norm() <= 0) return std::nullopt;
  for (const char* name : {"sternal_notch", "xiphoid"})
    if (const LandmarkTarget* t = find_landmark(landmarks, name); t && name != skip) {
      sum += t->position;
      ++points;
    }
  return MidPlane{sum / points, right_to_left.normalized()};
}

std::optional<Vec3> midline_notch_on_scan(const Points& scan_vertices, const std::vector<LandmarkTarget>& landmarks,
                                          const Vec3& near, const Vec3& up, const Vec3& front) {
  const auto plane = landmark_midplane(landmarks, "sternal_notch");
  if (!plane) return std::nullopt;
  const Vec3 on_plane = near - (near - plane->point).dot(plane->normal) * plane->normal;
  return jugular_notch_on_scan(scan_vertices, on_plane, up, front);
}

std::optional<NotchCheck> check_notch_on_midline(const Points& scan_vertices,
                                                 const std::vector<LandmarkTarget>& landmarks, const Vec3& near,
                                                 const Vec3& up, const Vec3& front, const Vec3& given,
                                                 double tolerance_mm) {
  const auto found = midline_notch_on_scan(scan_vertices, landmarks, near, up, front);
  if (!found) return std::nullopt;
  NotchCheck c;
  c.found = *found;
  const Vec3 d = given - *found;
  c.distance_mm = d.norm();
  const double side = d.dot(up.cross(front)) / tolerance_mm, vertical = d.dot(up) / (1.5 * tolerance_mm);
  const double scaled = std::sqrt(side * side + vertical * vertical);
  // The ellipse's radius along d (its front-back part, along the skin's normal, is not limited).
  c.tolerance_mm = scaled > 0 ? c.distance_mm / scaled : tolerance_mm;
  return c;
}

}  // namespace breastfit::fit
