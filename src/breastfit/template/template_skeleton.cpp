#include "breastfit/template/template_skeleton.h"

#include <algorithm>
#include <cmath>

namespace breastfit::templ {
namespace {

double smoothstep(double e0, double e1, double x) {
  double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

/// Orthonormal right-handed axes with the first column along `first` and the second as close as
/// possible to `hint`.
Mat3 frame(const Vec3& first, const Vec3& hint) {
  const Vec3 e1 = first.normalized();
  Vec3 e2 = hint - hint.dot(e1) * e1;
  e2.normalize();
  Mat3 R;
  R.col(0) = e1;
  R.col(1) = e2;
  R.col(2) = e1.cross(e2);
  return R;
}

constexpr double kThoraxPivotZ = -250.0;  // ~T12 (thoraco-lumbar junction)

// Scale-prior stiffness of a breast bone's two in-plane axes (along the chest wall); its
// projection axis keeps 1. A breast's base (2nd–6th rib, sternal border to the anterior axillary
// line) varies far less between women than its projection, and the in-plane scales drag the
// footprint's border — the breast contour — with them (the contour's top has breast-bone weight
// ~0.7). Bench (14 cases): 5 moved the transferred contours from 4.80 / 5.33 to 4.63 / 4.81 mm
// at +0.04 mm true-surface error (docs/TEMPLATE.md).
constexpr double kBreastBaseStiffness = 5.0;

}  // namespace

Vec3 acromion_point(const BodyField& field, int side) {
  const Vec3& J = field.shoulder_joint(side);
  const double s = side == 0 ? -1.0 : 1.0;
  return Vec3(J.x() + s * 12.0, J.y() + 16.0, J.z() + 30.0);
}

std::vector<model::Bone> template_bones(const BodyField& field) {
  const BodyParams& P = field.params();
  std::vector<model::Bone> b(kNumTemplateBones);
  auto centre_y = [&](double z) {
    double w, f, k, n;
    field.trunk_profile(z, &w, &f, &k, &n);
    return std::make_pair(f, k);
  };
  {
    const double z = 0.5 * (P.waist_cut_z + kThoraxPivotZ);
    const auto [f, k] = centre_y(z);
    b[kAbdomen].name = "abdomen";
    b[kAbdomen].pivot = Vec3(0, 0.5 * (f + k), z);
    b[kAbdomen].scale_lo = Vec3::Constant(0.7);
    b[kAbdomen].scale_hi = Vec3::Constant(1.4);
  }
  {
    const auto [f, k] = centre_y(kThoraxPivotZ);
    b[kThorax].name = "thorax";
    b[kThorax].parent = kAbdomen;
    b[kThorax].pivot = Vec3(0, k - 0.3 * (k - f), kThoraxPivotZ);  // vertebral body, near the back
    b[kThorax].scale_lo = Vec3::Constant(0.7);
    b[kThorax].scale_hi = Vec3::Constant(1.4);
  }
  {
    b[kNeck].name = "neck";
    b[kNeck].parent = kThorax;
    b[kNeck].pivot = Vec3(0, P.neck_center_y + 10.0, 5.0);
    b[kNeck].scale_lo = Vec3::Constant(0.6);
    b[kNeck].scale_hi = Vec3::Constant(1.6);
  }
  for (int side = 0; side < 2; ++side) {
    const double s = side == 0 ? -1.0 : 1.0;
    const Vec3 sc(s * 22.0, 14.0, -8.0);  // sterno-clavicular joint
    const Vec3 ac = acromion_point(field, side);
    model::Bone& c = b[side == 0 ? kClavicleR : kClavicleL];
    c.name = side == 0 ? "clavicle_R" : "clavicle_L";
    c.parent = kThorax;
    c.pivot = sc;
    c.axes = frame(ac - sc, Vec3::UnitZ());
    c.scale_lo = Vec3::Constant(0.7);
    c.scale_hi = Vec3::Constant(1.4);

    model::Bone& a = b[side == 0 ? kUpperArmR : kUpperArmL];
    a.name = side == 0 ? "upper_arm_R" : "upper_arm_L";
    a.parent = side == 0 ? kClavicleR : kClavicleL;
    a.pivot = field.shoulder_joint(side);
    a.axes = frame(field.humerus_dir(side), Vec3::UnitY());
    a.scale_lo = Vec3::Constant(0.7);
    a.scale_hi = Vec3::Constant(1.5);

    const BreastFrame& fr = field.breast_frame(side);
    model::Bone& br = b[side == 0 ? kBreastR : kBreastL];
    br.name = side == 0 ? "breast_R" : "breast_L";
    br.parent = kThorax;
    br.pivot = fr.base_center;
    br.axes = frame(fr.w, fr.v);
    br.scale_lo = Vec3::Constant(0.5);
    br.scale_hi = Vec3::Constant(2.0);
    br.scale_stiffness = Vec3(1.0, kBreastBaseStiffness, kBreastBaseStiffness);  // axes: w (projection), v, lateral
  }
  return b;
}

Eigen::VectorXd breast_height(const TriangleMesh& mesh, const BodyField& field) {
  Eigen::VectorXd h(mesh.num_vertices());
  for (Index v = 0; v < mesh.num_vertices(); ++v)
    h[v] = std::max(0.0, field.value_without_breasts(mesh.V.row(v).transpose()));
  return h;
}

Eigen::MatrixXd skin_weight_seeds(const TemplateMesh& tm, const BodyField& field,
                                  const Eigen::VectorXd& bh) {
  const TriangleMesh& m = tm.mesh;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(m.num_vertices(), kNumTemplateBones);
  const double bmax = std::max(bh.maxCoeff(), 1e-9);
  for (Index v = 0; v < m.num_vertices(); ++v) {
    const Vec3 p = m.V.row(v).transpose();
    const int side = p.x() < 0 ? 0 : 1;
    const Vec3& J = field.shoulder_joint(side);
    const Vec3& d = field.humerus_dir(side);
    const double t = (p - J).dot(d);
    const double radial = ((p - J) - t * d).norm();
    const ArmParams& ap = field.params().arm[side];
    int bone;
    // The deltoid cap and the arm from just above the joint move with the humerus: with a
    // later start the raised arm (supine, 65-95 deg) drags the shoulder and the pectoral fold.
    if (t > -10.0 && radial < ap.radius_top + 12.0 && std::abs(p.x()) > 120.0) {
      bone = side == 0 ? kUpperArmR : kUpperArmL;
    } else if (std::abs(p.x()) > 75.0 && p.z() > J.z() - 25.0 && (p - J).norm() < 130.0) {
      bone = side == 0 ? kClavicleR : kClavicleL;
    } else if (p.z() > 12.0 && std::abs(p.x()) < 80.0) {
      bone = kNeck;
    } else if (p.z() < kThoraxPivotZ - 20.0) {
      bone = kAbdomen;
    } else {
      bone = kThorax;
    }
    const double b = smoothstep(0.0, 0.45, bh[v] / bmax);
    S(v, bone) = 1.0 - b;
    S(v, side == 0 ? kBreastR : kBreastL) += b;
  }
  return S;
}

}  // namespace breastfit::templ
