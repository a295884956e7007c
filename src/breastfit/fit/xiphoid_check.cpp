#include "breastfit/fit/xiphoid_check.h"

namespace breastfit::fit {

double xiphoid_residual_mm(const Vec3& notch, const Vec3& xiphoid, const Vec3& lowest_breast_R,
                           const Vec3& lowest_breast_L, const Vec3& up) {
  const double depth = -0.5 * ((lowest_breast_R - notch).dot(up) + (lowest_breast_L - notch).dot(up));
  return (notch - xiphoid).dot(up) - depth / kLowestBreastSternumLengths;
}

}  // namespace breastfit::fit
