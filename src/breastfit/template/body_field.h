#pragma once
/// \file The parametric implicit body: a smooth, distance-like field (negative inside, about
/// millimetres near the surface) built from a superellipse trunk profile, neck, deltoids, arms
/// and two breasts combined by smooth unions, plus the cut planes that open it at the waist,
/// the neck base and mid-humerus. Body frame LPS, origin at the sternal notch.
#include <array>
#include <limits>
#include <vector>

#include "breastfit/core/types.h"
#include "breastfit/template/body_params.h"

namespace breastfit::templ {

/// A plane that removes the part of the body on its positive side, optionally only within
/// `region_radius` of a line (so that the arm cut does not slice the trunk).
struct CutPlane {
  Vec3 point = Vec3::Zero();   ///< a point of the plane, mm
  Vec3 normal = Vec3::UnitZ(); ///< unit normal pointing into the removed part
  Vec3 region_point = Vec3::Zero();  ///< a point of the region axis
  Vec3 region_dir = Vec3::UnitZ();   ///< unit direction of the region axis
  double region_radius = std::numeric_limits<double>::infinity();  ///< mm

  /// Signed distance to the plane (> 0 in the removed half-space).
  double signed_distance(const Vec3& p) const { return normal.dot(p - point); }
  /// True when p is within the region of this cut.
  bool in_region(const Vec3& p) const;
  /// True when p is removed by this cut (in the region and on the positive side).
  bool removes(const Vec3& p) const { return in_region(p) && signed_distance(p) > 0.0; }
};

/// Frame of one breast (columns u lateral, v cranial, w forward along the axis).
struct BreastFrame {
  Vec3 base_center = Vec3::Zero();  ///< centre of the base on the chest wall, mm
  Vec3 center = Vec3::Zero();       ///< ellipsoid centre (behind the base), mm
  Vec3 u = Vec3::UnitX(), v = Vec3::UnitZ(), w = -Vec3::UnitY();
  Vec3 nipple = Vec3::Zero();       ///< rest position of the apex material point, mm
};

class BodyField {
 public:
  /// \throws InvalidInput when the trunk profile has fewer than 3 knots or bad values.
  explicit BodyField(const BodyParams& params);

  const BodyParams& params() const { return params_; }

  /// Field value at p (mm; < 0 inside).
  double value(const Vec3& p) const;
  /// Field without the breasts (the chest wall); value(p) <= value_without_breasts(p).
  double value_without_breasts(const Vec3& p) const;
  /// Central-difference gradient of value().
  Vec3 gradient(const Vec3& p) const;
  /// Unit outward normal (normalised gradient).
  Vec3 normal(const Vec3& p) const;

  /// Newton projection of p onto the zero set.
  Vec3 project(const Vec3& p, int iterations = 6) const;
  /// Projection onto the intersection of the zero set with a plane (point, unit normal).
  Vec3 project_on_plane(const Vec3& p, const Vec3& plane_point, const Vec3& plane_normal,
                        int iterations = 8) const;
  /// Projection onto the intersection of the zero set with two planes (a corner of two cuts).
  Vec3 project_on_two_planes(const Vec3& p, const CutPlane& a, const CutPlane& b,
                             int iterations = 8) const;
  /// Root of value(p + t d) = 0 nearest to t = 0 within [-max_t, max_t] (d unit); nullopt-like
  /// NaN when there is none.
  double ray_root(const Vec3& p, const Vec3& d, double max_t) const;

  /// Breast frame of side 0 = right (x < 0) or 1 = left (x > 0).
  const BreastFrame& breast_frame(int side) const { return breast_frames_[side]; }
  /// Gleno-humeral joint centre and unit humerus direction (downwards) of a side.
  const Vec3& shoulder_joint(int side) const { return joints_[side]; }
  const Vec3& humerus_dir(int side) const { return humerus_dirs_[side]; }
  /// Trunk profile at height z: half width, front and back y (modifiers applied, at x = 0).
  void trunk_profile(double z, double* half_width, double* front_y, double* back_y,
                     double* exponent) const;
  /// y of the anterior trunk surface (no breasts) at (x, z), by bisection on the trunk field.
  double trunk_front_y(double x, double z) const;

  /// The cut planes for the whole body: waist, neck, arm_R, arm_L.
  std::vector<CutPlane> cut_planes() const;
  /// Cut of the right (side 0) or left (side 1) arm.
  CutPlane arm_cut(int side) const;
  CutPlane waist_cut() const;
  CutPlane neck_cut() const;

  /// Per-part values at p (for region assignment): trunk, neck, arm side, breast side.
  double trunk_value(const Vec3& p) const;
  double neck_value(const Vec3& p) const;
  double arm_value(const Vec3& p, int side) const;
  double breast_value(const Vec3& p, int side) const;

 private:
  double body_value(const Vec3& p, bool with_breasts) const;
  BodyParams params_;
  // Trunk profile channels, ascending z, with PCHIP slopes.
  std::vector<double> kz_;
  std::array<std::vector<double>, 4> kv_, ks_;  // half_width, front, back, exponent
  std::array<BreastFrame, 2> breast_frames_;
  std::array<Vec3, 2> joints_, humerus_dirs_;
};

}  // namespace breastfit::templ
