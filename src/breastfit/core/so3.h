#pragma once
/// \file Rotation helpers: skew matrix, exponential and logarithm of SO(3), inverse left Jacobian.
#include <cmath>

#include "breastfit/core/types.h"

namespace breastfit {

/// [v]× such that [v]× x = v × x.
inline Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// exp([w]×) as a unit quaternion.
inline Quat exp_so3(const Vec3& w) {
  const double theta = w.norm();
  if (theta < 1e-12) return Quat(1.0, 0.5 * w.x(), 0.5 * w.y(), 0.5 * w.z()).normalized();
  return Quat(Eigen::AngleAxisd(theta, w / theta));
}

/// log(R) as a rotation vector (angle in [0, π] times the unit axis).
inline Vec3 log_so3(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0) q.coeffs() *= -1.0;  // shortest rotation
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  const double angle = 2.0 * std::atan2(s, q.w());
  return (angle / s) * v;
}

/// J_l(φ)⁻¹: d log(exp([δ]×) exp([φ]×)) / dδ at δ = 0.
inline Mat3 left_jacobian_inverse(const Vec3& phi) {
  const double theta = phi.norm();
  const Mat3 K = skew(phi);
  if (theta < 1e-6) return Mat3::Identity() - 0.5 * K + (1.0 / 12.0) * K * K;
  const double half = 0.5 * theta;
  const double coef = (1.0 - half * std::cos(half) / std::sin(half)) / (theta * theta);
  return Mat3::Identity() - 0.5 * K + coef * K * K;
}

}  // namespace breastfit
