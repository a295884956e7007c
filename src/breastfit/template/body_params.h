#pragma once
/// \file The anatomical parameters of the parametric implicit body the default template is
/// generated from (docs/TEMPLATE.md). Millimetres and degrees; body frame LPS (x = patient left,
/// y = posterior, z = superior) with the origin at the sternal notch.
#include <array>
#include <vector>

namespace breastfit::templ {

/// One knot of the trunk profile: the horizontal cross-section at height z is a superellipse
/// |x/half_width|^n + |(y - yc)/depth|^n = 1 with yc = (front_y + back_y)/2 and
/// depth = (back_y - front_y)/2, interpolated between knots (monotone cubic, C1).
struct TrunkKnot {
  double z;           ///< height, mm (0 at the sternal notch)
  double half_width;  ///< half the left-right width, mm
  double front_y;     ///< anterior extent on the midline (y, negative = anterior), mm
  double back_y;      ///< posterior extent on the midline, mm
  double exponent;    ///< superellipse exponent (2 = ellipse, larger = boxier)
};

/// One breast, described in its own frame: w along the breast axis (forward), u lateral,
/// v cranial. The breast is an ellipsoid (different cranial and caudal radii) sunk into the
/// chest wall, blended into the trunk, with a ptosis warp that lowers points by
/// ptosis_mm * (forward fraction)^2.
struct BreastParams {
  double base_x = 88.0;          ///< |x| of the base centre (on the chest wall), mm
  double base_z = -178.0;        ///< z of the base centre, mm
  double axis_lateral_deg = 17;  ///< breast axis turned laterally from straight anterior, deg
  double axis_down_deg = 6;      ///< breast axis tilted caudally, deg
  double roll_deg = 12;          ///< frame turned about the axis so that the lower pole lies medially, deg
  double radius_lateral = 62.0;  ///< semi-axis across (u), mm
  double radius_upper = 70.0;    ///< semi-axis towards the head (v > 0), mm
  double radius_lower = 78.0;    ///< semi-axis towards the feet (v < 0), mm
  double depth = 76.0;           ///< semi-axis along the breast axis (w), mm
  double sink = 30.0;            ///< the ellipsoid centre lies this far behind the base centre, mm
  double ptosis_mm = 10.0;       ///< drop of the apex (nipple) by the ptosis warp, mm
  double upper_slope = 0.3;      ///< 0 = elliptic upper pole; > 0 straighter slope (upper radius shrinks forwards)
  double upper_fullness = 0.0;   ///< > 0 fills the upper pole (more projection above the apex)
  double lower_fullness = 0.0;   ///< > 0 fills the lower pole
  double blend_upper_mm = 18.0;  ///< smooth-union radius at the upper pole, mm
  double blend_lower_mm = 9.0;   ///< smooth-union radius at the fold (sharper crease), mm
};

/// One arm (upper arm to mid-humerus) with its deltoid.
struct ArmParams {
  double joint_x = 160.0;        ///< |x| of the gleno-humeral joint centre, mm
  double joint_y = 42.0;         ///< y of the joint centre, mm
  double joint_z = -47.0;        ///< z of the joint centre, mm
  double abduction_deg = 24.0;   ///< humerus axis away from the vertical, in the coronal plane
  double flexion_deg = 3.0;      ///< humerus axis forwards (sagittal), deg
  double radius_top = 46.0;      ///< arm radius at the joint, mm
  double radius_mid = 42.0;      ///< arm radius at the cut (mid-humerus), mm
  double cut_length = 150.0;     ///< distance joint -> cut plane along the humerus, mm
  double deltoid_radius = 47.0;  ///< horizontal radius of the deltoid cap, mm
  double deltoid_height = 40.0;  ///< vertical radius of the deltoid cap, mm
};

/// The whole body. Defaults: an average adult woman (B cup, moderately firm), calibrated to
/// typical adult dimensions (notch-xiphoid 205 mm, inter-nipple ~200 mm, chest width ~300 mm).
struct BodyParams {
  std::vector<TrunkKnot> trunk = default_trunk();
  // Global modifiers (blendshape handles); 1 / 0 = the rest shape.
  double chest_width_scale = 1.0;    ///< multiplies half_width for -250 < z < -20
  double waist_width_scale = 1.0;    ///< multiplies half_width around z = -290
  double hip_width_scale = 1.0;      ///< multiplies half_width below z = -320
  double chest_depth_scale = 1.0;    ///< scales front/back about the centre for -260 < z < -20
  double abdomen_protrusion_mm = 0;  ///< moves the anterior abdomen forward (z < -240)
  double kyphosis_mm = 0;            ///< moves the upper back backwards (bump at z ~ -90)
  double upper_chest_mm = 0;         ///< moves the upper anterior chest forward (z ~ -60)
  double back_width_scale = 1.0;     ///< widens the posterior half of the chest (latissimus)
  double shoulder_slope_mm = 0;      ///< raises (>0) the trapezius line between neck and acromion
  double neck_radius_scale = 1.0;    ///< scales the neck cross-section
  double neck_center_y = 52.0;       ///< y of the neck axis at its base, mm
  double neck_radius_x = 56.0;       ///< neck half-width, mm
  double neck_radius_y = 48.0;       ///< neck half-depth, mm
  double neck_tilt_deg = 12.0;       ///< forward tilt of the neck axis, deg
  std::array<BreastParams, 2> breast{};  ///< [0] = right (x < 0), [1] = left (x > 0)
  std::array<ArmParams, 2> arm{};        ///< [0] = right, [1] = left
  double blend_neck_mm = 28.0;       ///< smooth-union radius trunk/neck, mm
  double blend_arm_mm = 26.0;        ///< smooth-union radius trunk/arm and arm/deltoid, mm
  // Cuts.
  double waist_cut_z = -355.0;       ///< z of the horizontal cut at the umbilicus, mm
  double neck_cut_z = 40.0;          ///< z of the neck cut on the neck axis, mm
  double neck_cut_tilt_deg = 15.0;   ///< the neck cut rises posteriorly by this angle, deg

  /// The default profile (z from the neck down to below the umbilicus).
  static std::vector<TrunkKnot> default_trunk() {
    return {
        // z      hw     front   back   n
        {60.0, 28.0, 40.0, 90.0, 2.2},    {35.0, 60.0, 26.0, 96.0, 2.3},
        {18.0, 104.0, 12.0, 104.0, 2.7},  {4.0, 140.0, 2.0, 111.0, 3.0},
        {-12.0, 156.0, -8.0, 118.0, 3.0}, {-35.0, 160.0, -24.0, 124.0, 2.8},
        {-65.0, 158.0, -40.0, 128.0, 2.6}, {-100.0, 154.0, -50.0, 128.0, 2.5},
        {-140.0, 150.0, -58.0, 124.0, 2.4}, {-180.0, 145.0, -63.0, 117.0, 2.4},
        {-220.0, 138.0, -66.0, 110.0, 2.35}, {-260.0, 128.0, -68.0, 104.0, 2.3},
        {-295.0, 124.0, -70.0, 100.0, 2.3}, {-335.0, 130.0, -73.0, 102.0, 2.3},
        {-375.0, 138.0, -76.0, 108.0, 2.3}, {-420.0, 144.0, -77.0, 114.0, 2.3},
    };
  }
};

}  // namespace breastfit::templ
