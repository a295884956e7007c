#include "breastfit/fit/pectoral_pair_check.h"

#include <algorithm>
#include <cmath>

namespace breastfit::fit {
namespace {

// The difference's ellipsoid at landmark_check_mm = 15 (pectoral_pair_check.h): along the sternum,
// front, sideways.
const Vec3 kPairTolerance(13.0, 20.0, 13.0);
// The single insertion's ellipsoid (pectoral_check.cpp), for the blame.
const Vec3 kOwnTolerance(16.0, 14.0, 22.0);

}  // namespace

PectoralPairCheck check_pectoral_pair(const PectoralCheck& right, const PectoralCheck& left, double landmark_check_mm) {
  PectoralPairCheck out;
  const Vec3 tolerance = kPairTolerance * (landmark_check_mm / 15.0);
  out.difference = right.deviation - left.deviation;
  out.distance_mm = out.difference.norm();
  const double relative = out.difference.cwiseQuotient(tolerance).norm();
  out.tolerance_mm = relative > 0 ? out.distance_mm / relative : tolerance.minCoeff();
  out.right_blamed =
      right.deviation.cwiseQuotient(kOwnTolerance).norm() >= left.deviation.cwiseQuotient(kOwnTolerance).norm();
  return out;
}

double pectoral_pair_tolerance_mm(const PectoralPairCheck& check, double predicted_ratio) {
  const double room = std::sqrt(std::max(kPectoralPairThreshold - predicted_ratio * predicted_ratio, 0.0));
  return check.tolerance_mm * std::max(room, 0.25);
}

}  // namespace breastfit::fit
