#include "breastfit/fit/nipple_apex_check.h"

#include <algorithm>

namespace breastfit::fit {

double height_above_apex_mm(const SternumFrame& frame, const Vec3& given, const Vec3& apex) {
  return (given - apex).dot(frame.up);
}

NippleApexCheck check_nipple_apex(const SternumFrame& frame, const Vec3& given, const Vec3& apex, double tip_ratio,
                                  std::optional<double> partner_up_mm) {
  NippleApexCheck c;
  const Vec3 d = given - apex;
  c.deviation = Vec3(d.dot(frame.lateral), height_above_apex_mm(frame, given, apex), d.dot(frame.front));
  c.distance_mm = d.norm();
  // Each rule as a scale: the deviation is beyond the rule's boundary by `relative` (> 1: flagged).
  double relative = 0;
  const auto rule = [&](double r, const char* what) {
    if (r > relative) {
      relative = r;
      c.rule = what;
    }
  };
  const double up = c.deviation.y(), front = c.deviation.z();
  if (up > 0) rule(up / kApexAboveMm, "above it");
  if (front < 0 && up > -kApexBehindAllowedBelowMm && tip_ratio > kApexBehindTipRatio)
    rule(-front / kApexBehindMm, "behind it");
  // Below: both conditions beyond their boundaries, so the nearer one is the rule's scale.
  if (partner_up_mm && up < 0)
    rule(std::min(-up / kApexBelowMm, (*partner_up_mm - up) / kApexBelowPartnerMm),
         "below it and lower on its breast than the other nipple");
  c.tolerance_mm = relative > 0 ? c.distance_mm / relative : c.distance_mm;
  return c;
}

}  // namespace breastfit::fit
