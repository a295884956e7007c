#include "breastfit/fit/landmark_check.h"

namespace breastfit::fit {

double landmark_check_tolerance_mm(const std::string& name, double landmark_check_mm) {
  return landmark_weight(name) < 1.0 ? 2.0 * landmark_check_mm : landmark_check_mm;
}

double robust_landmark_factor(double distance_mm, double tolerance_mm) {
  if (!(distance_mm > tolerance_mm)) return 1.0;
  const double q = tolerance_mm / distance_mm;
  return q * q;
}

}  // namespace breastfit::fit
