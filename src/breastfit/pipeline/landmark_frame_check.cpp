#include "breastfit/pipeline/landmark_frame_check.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace breastfit::pipeline {
namespace {

double median_distance(const std::vector<std::pair<std::string, Vec3>>& landmarks, const fit::ScanTarget& scan,
                       const std::function<Vec3(const Vec3&)>& map) {
  std::vector<double> d;
  for (const auto& [name, p] : landmarks) d.push_back(std::sqrt(scan.closest(map(p)).sq_dist));
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

}  // namespace

std::optional<LandmarkFrameDiagnosis> diagnose_landmark_frame(const std::vector<std::pair<std::string, Vec3>>& landmarks,
                                                              const fit::ScanTarget& scan, double off_scan_mm,
                                                              double on_scan_mm) {
  if (landmarks.size() < 3) return std::nullopt;
  LandmarkFrameDiagnosis out;
  out.median_distance_mm = median_distance(landmarks, scan, [](const Vec3& p) { return p; });
  if (out.median_distance_mm <= off_scan_mm) return std::nullopt;
  const auto flip = [](const Vec3& p) { return Vec3(-p.x(), -p.y(), p.z()); };
  const std::vector<std::pair<std::string, std::function<Vec3(const Vec3&)>>> mistakes = {
      {"x and y negated (RAS read as LPS, or the reverse)", flip},
      {"in metres but read as millimetres (a factor 1000)", [](const Vec3& p) { return Vec3(p * 1000.0); }},
      {"in millimetres but read as metres (a factor 1000)", [](const Vec3& p) { return Vec3(p / 1000.0); }},
      {"x and y negated and in metres read as millimetres", [&](const Vec3& p) { return Vec3(flip(p) * 1000.0); }},
      {"x and y negated and in millimetres read as metres", [&](const Vec3& p) { return Vec3(flip(p) / 1000.0); }},
  };
  for (const auto& [what, map] : mistakes) {
    const double m = median_distance(landmarks, scan, map);
    if (m <= on_scan_mm) {
      out.mistake = what;
      out.corrected_median_mm = m;
      return out;
    }
  }
  return std::nullopt;
}

}  // namespace breastfit::pipeline
